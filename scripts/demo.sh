#!/usr/bin/env bash
# The README's first command: installs what is missing, builds the renderer
# (build/bin/pathtracer only: the test suite is scripts/test.sh's), and
# renders the demo scene to out/demo.png, with a progress line for each.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/demo.sh
Installs what is missing (scripts/setup.sh), builds build/bin/pathtracer only (about 60
CPU-seconds of compiling, so about 30 s on 2 idle cores; the tests are built by
scripts/test.sh) and renders the path-traced Cornell box to out/demo.png (about 7 s on 2 cores).
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null

# Measured: a clean build of the pathtracer target is 59 files and 58
# CPU-seconds (GCC 12, -O3, AMD EPYC); a busy machine takes longer.
cores=$(nproc)
load=$(cut -d' ' -f1 /proc/loadavg)
estimate=$(( (60 + cores - 1) / cores ))
note=""
if awk -v l="$load" -v c="$cores" 'BEGIN { exit !(l > c / 2) }'; then
  note=" when idle; the load average is $load, so expect longer"
fi
log=build/demo_build.log
echo "demo: building build/bin/pathtracer only (a first build compiles about 60 files: about ${estimate} s on ${cores} cores${note}); log in $log"

# One progress line from make's "[ 45%] Building CXX object ..." lines:
# redrawn in place on a terminal, one line per 10% otherwise.
progress() {
  local start=$SECONDS last=-10 line pct file
  while IFS= read -r line; do
    printf '%s\n' "$line" >> "$log"
    [[ $line =~ ^\[\ *([0-9]+)%\]\ (Building|Linking)\ CXX\ (object|executable)\ (.*)$ ]] || continue
    pct=${BASH_REMATCH[1]}
    file=${BASH_REMATCH[4]##*/}
    file=${file%.o}
    if [ -t 1 ]; then
      printf '\r\033[Kdemo: building %3d%% %-36s %d s' "$pct" "$file" $((SECONDS - start))
    elif [ "$pct" -ge $((last + 10)) ]; then
      echo "demo: building $pct% ($((SECONDS - start)) s)"
      last=$pct
    fi
  done
  [ -t 1 ] && printf '\r\033[K'
  return 0
}

: > "$log"
start=$SECONDS
if ! cmake --build build -j "$cores" --target pathtracer 2>&1 | progress; then
  echo "demo: the build failed; the end of $log:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
echo "demo: built build/bin/pathtracer in $((SECONDS - start)) s"

mkdir -p out
# Path-traced Cornell box with a mirror and a glass sphere: 5 bounces,
# 256 samples per pixel (about 7 s on 2 cores); the progress bar is on stderr.
build/bin/pathtracer -t "$cores" -r 320 240 -s 256 -m 5 -f out/demo.png assets/scenes/cbox_spheres.json
echo "demo: wrote out/demo.png"
