#!/usr/bin/env bash
# The README's second command: installs what is missing, builds, and runs
# the whole ctest suite (unit, statistical, image, grading and CLI tests).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)"
