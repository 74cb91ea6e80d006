#!/usr/bin/env bash
# Configures a Release build into build/ and builds every executable into
# build/bin/ (the DESIGN.md build command). Extra arguments go to cmake's
# configure step, e.g. scripts/build.sh -DPT_STUDENT_DIR=/path/to/assignments
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j "$(nproc)"
