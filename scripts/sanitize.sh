#!/usr/bin/env bash
# Builds the project and its tests with AddressSanitizer and
# UndefinedBehaviorSanitizer into build-asan/ and runs the whole suite.
# Slower than scripts/test.sh (about 3x), so it is a separate command.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/sanitize.sh
Builds the project and its tests with AddressSanitizer and UndefinedBehaviorSanitizer into
build-asan/ and runs the whole suite (about 3 times as long as scripts/test.sh).
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPT_SANITIZE=ON >/dev/null
cmake --build build-asan -j "$(nproc)"
cd build-asan
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$(nproc)"
