#!/usr/bin/env bash
# Configures a Release build into build/ and builds every executable into
# build/bin/ (the DESIGN.md build command). Extra arguments go to cmake's
# configure step, e.g. scripts/build.sh -DPT_STUDENT_DIR=/path/to/assignments
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/build.sh [CMAKE_CONFIGURE_OPTION...]
Installs what is missing (scripts/setup.sh), configures a Release build in build/ with the
given options (e.g. -DPT_STUDENT_DIR=/path/to/assignments) and builds every target.
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j "$(nproc)"
