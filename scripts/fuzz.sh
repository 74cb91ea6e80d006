#!/usr/bin/env bash
# Fuzzes the scene and OBJ loaders with libFuzzer (clang, with ASan and
# UBSan) for a bounded time, starting from tests/fuzz/corpus.
# Usage: scripts/fuzz.sh [SECONDS=60]. New interesting inputs are left in
# build-fuzz/corpus; copy the small ones worth keeping to tests/fuzz/corpus.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/fuzz.sh [SECONDS=60]
Fuzzes the scene and OBJ loaders with libFuzzer (clang, ASan, UBSan) for SECONDS, from
tests/fuzz/corpus; new inputs are left in build-fuzz/corpus.
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
seconds=${1:-60}
scripts/setup.sh clang libclang-rt-14-dev
CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPT_FUZZ=ON -DPT_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_scene_loader
mkdir -p build-fuzz/corpus
build-fuzz/bin/fuzz_scene_loader build-fuzz/corpus tests/fuzz/corpus \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1
