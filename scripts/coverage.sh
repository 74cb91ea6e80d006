#!/usr/bin/env bash
# Coverage of the graded cases (issue 15): builds the handout-steps solution
# (tests/grading/solution, or $PT_COVERAGE_SOLUTION) with gcov counters on the
# student's files only, grades it (--timeout 0: unoptimised code is slow),
# and prints per task and function the lines
# and branches of the solution that no graded case ran, less the exclusions
# listed in the manifests ("coverage_exclusions", each with its reason).
# The student code runs in grade's runners (one process per task), which
# write their counters before they exit (__gcov_dump); they run without
# bubblewrap (--no-sandbox) so that they can write them into the build
# folder: the solution is ours, not a student's.
#
#   scripts/coverage.sh [BUILD_DIR]        (default build-coverage)
#
# PT_COVERAGE_TASKS=part8.1,part8.2 grades and reports only those tasks (a
# quick look at one part; the rule is the full run).
#
# Exit code: 0 when everything outside the exclusions ran, 1 when something
# did not, 2 when the build or the grading failed. Takes a few minutes: one
# more build folder (ccache makes the engine's objects cheap), then a grade.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-coverage}
solution=${PT_COVERAGE_SOLUTION:-$root/tests/grading/solution}
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

mkdir -p "$build"
# The student folder: the handout's files (stubs for what the solution does
# not cover, e.g. later parts), overlaid with the solution's.
student="$build/student"
rm -rf "$student"
cp -r "$root/assignments" "$student"
cp -r "$solution"/part* "$student"/
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPT_BUILD_TESTS=OFF \
  -DPT_STUDENT_DIR="$student" -DPT_STUDENT_COVERAGE=ON "${launcher[@]}" > "$build/configure.log" 2>&1 ||
  { echo "coverage: cmake failed, see $build/configure.log" >&2; exit 2; }
cmake --build "$build" -j2 --target grade > "$build/build.log" 2>&1 ||
  { echo "coverage: the build failed, see $build/build.log" >&2; exit 2; }
find "$build" -name '*.gcda' -delete
status=0
task_flags=()
[ -n "${PT_COVERAGE_TASKS:-}" ] && task_flags=(--task "$PT_COVERAGE_TASKS")
"$build/bin/grade" "${task_flags[@]}" --no-sandbox --timeout 0 -q -t 2 --out "$build/coverage_grade" \
  --manifests "$root/assignments" --assets "$root/assets" || status=$?
if [ "$status" -ge 2 ]; then
  echo "coverage: grade failed (exit $status)" >&2
  exit 2
fi
[ "$status" -eq 0 ] || echo "coverage: note: the solution did not earn full marks (see $build/coverage_grade/report.md)"
python3 "$root/scripts/coverage_report.py" "$build" "$student" "$root/assignments" "$solution"
