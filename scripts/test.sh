#!/usr/bin/env bash
# The README's second command: installs what is missing, builds, and runs
# the whole ctest suite (unit, statistical, image, grading and CLI tests).
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/test.sh
Installs what is missing (scripts/setup.sh), builds everything into build/ and runs the
whole ctest suite (about 8 minutes on 2 cores after the build). Exit 0 when every test passes.
To run some tests only: cd build && ctest -R 'cli/' -j2
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)"
