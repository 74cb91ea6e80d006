#!/usr/bin/env bash
# False-failure rate of the grading cases added by issue 15 (and of Part 9's
# image task): the reference
# graded as the student on many seeds, each case's failures counted
# (docs/grading.md, "Measured false-failure rate and power").
#
#   scripts/false_failure.sh [-n SEEDS] [-s FIRST] [-j JOBS] [-c CHUNK] [-g GROUPS] [BUILD_DIR]
#
# SEEDS per case (default 1000) from seed FIRST (default 1: -s 551 -n 450
# extends a run of seeds 1 to 550 to 1000 in a fresh build folder), split into chunks of CHUNK seeds (default
# 25) run by JOBS processes at once (default 2; each renders with 2
# threads). It needs BUILD_DIR/tests/test_grading (default build). Every
# chunk's log is kept in BUILD_DIR/false_failure/, so a run that is stopped
# (or given a deadline: PT_FALSE_FAILURE_UNTIL=epoch seconds, after which no
# chunk starts) resumes where it stopped, and the summary counts the seeds
# that were run: per case, failures, seeds, the largest error ratio and
# worst-tile |z|, and the 95% upper bound of the rate (3 / seeds when none
# failed; the exact Clopper-Pearson bound otherwise). GROUPS: a comma list
# of the group names below (default all). The cases are graded as the
# manifests grade them, same sizes and sample counts: a cheaper image would
# measure another rule (fewer tiles, fewer tests).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seeds=1000 start=1 jobs=2 chunk=25 groups=""
usage="usage: scripts/false_failure.sh [-n SEEDS] [-s FIRST] [-j JOBS] [-c CHUNK] [-g GROUPS] [BUILD_DIR]"
while getopts "n:s:j:c:g:" opt; do
  case $opt in
    n) seeds=$OPTARG ;;
    s) start=$OPTARG ;;
    j) jobs=$OPTARG ;;
    c) chunk=$OPTARG ;;
    g) groups=$OPTARG ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
for v in "-n:$seeds" "-s:$start" "-j:$jobs" "-c:$chunk"; do
  [[ ${v#*:} =~ ^[1-9][0-9]*$ ]] || { echo "false_failure: ${v%%:*} needs a positive integer, got '${v#*:}'" >&2; exit 2; }
done
shift $((OPTIND - 1))
build=${1:-$root/build}
tests=$build/tests/test_grading
[ -x "$tests" ] || { echo "false_failure: $tests is not built (cmake --build $build --target test_grading)" >&2; exit 2; }
out=$build/false_failure
mkdir -p "$out"

# name|part|task|case label substrings ('|'-separated in the label list: ';' here)|functions
all_groups=(
  "film|1|part1.2|47x29|0"
  "slab|2|part2.2||1"
  "hemisphere|3|part3.4|every kind;Whitted|0"
  "lights|3|part3.5|every kind|0"
  "sky41|4|part4.1|mirror, glass and sky|0"
  "sky42|4|part4.2|sky|0"
  "mis38|3|part3.8|a mirror, rough gold|0"
  "pane38|3|part3.8|frosted-glass pane|0"
  "gold41|4|part4.1|rough gold and frosted glass|0"
  "fog95|9|part9.5|box of fog|0"
  "panel95|9|part9.5|panel light|0"
  "lights74|7|part7.4|every kind|0"
  "walk71|7|part7.1||1"
)

# Round-robin over the groups (the first chunk of every group, then the next
# chunk of every group), so that a run stopped early has measured every
# case on about as many seeds.
chunks=()
last=$((start + seeds - 1))
for ((first = start; first <= last; first += chunk)); do
  n=$((last - first + 1 < chunk ? last - first + 1 : chunk))
  for g in "${all_groups[@]}"; do
    IFS='|' read -r name part task cases functions <<< "$g"
    if [ -n "$groups" ] && [[ ",$groups," != *",$name,"* ]]; then continue; fi
    chunks+=("$name|$part|$task|$cases|$functions|$first|$n")
  done
done

run_chunk() {
  IFS='|' read -r name part task cases functions first n <<< "$1"
  local log=$out/$name.$first.$n.log
  [ -f "$log" ] && grep -q '^\[doctest\] Status: SUCCESS' "$log" && return 0
  if [ -n "${PT_FALSE_FAILURE_UNTIL:-}" ] && [ "$(date +%s)" -ge "$PT_FALSE_FAILURE_UNTIL" ]; then return 0; fi
  PT_CALIBRATION_PARTS=$part PT_CALIBRATION_TASKS=$task PT_CALIBRATION_CASES=${cases//;/|} \
    PT_CALIBRATION_SEEDS=$n PT_CALIBRATION_FIRST_SEED=$first PT_CALIBRATION_FIXTURES=0 \
    PT_CALIBRATION_FUNCTIONS=$functions \
    nice "$tests" -tc="calibration*" --no-skip > "$log.tmp" 2>&1 && mv "$log.tmp" "$log" ||
    echo "false_failure: chunk $name seeds $first.. failed to run, see $log.tmp" >&2
}
export -f run_chunk
export out tests

# The first chunk of each group one at a time: it renders the converged
# references into the test cache that the others then share.
first_round=$(printf '%s\n' "${chunks[@]}" | awk -F'|' -v s="$start" '$6 == s' | wc -l)
for c in "${chunks[@]:0:$first_round}"; do run_chunk "$c"; done
printf '%s\n' "${chunks[@]:$first_round}" | xargs -r -P "$jobs" -I{} bash -c 'run_chunk "$@"' _ {}

python3 - "$out" <<'EOF'
import glob, math, os, re, sys
out = sys.argv[1]
cases = {}  # (task, label) -> [failures, seeds, max ratio, max z]
for log in sorted(glob.glob(os.path.join(out, "*.log"))):
    task, label, seeds = None, None, 0
    for line in open(log):
        m = re.match(r"reference as student, (\S+), (\d+) seeds: (\d+) task failures", line)
        if m:
            task, seeds = m.group(1), int(m.group(2))
            # the whole task's row: printed only for a task without case lines (a function check)
            e = cases.setdefault((task, "(the whole task)"), [0, 0, 0.0, 0.0])
            e[0] += int(m.group(3)); e[1] += seeds
            continue
        m = re.match(r"  case \d+ \((.*)\): (\d+) failures", line)
        if m and task:
            label = m.group(1)
            e = cases.setdefault((task, label), [0, 0, 0.0, 0.0])
            e[0] += int(m.group(2)); e[1] += seeds
            continue
        m = re.match(r"    (ratio|worst z): .*top three \S+ \S+ (\S+)", line)
        if m and label:
            i = 2 if m.group(1) == "ratio" else 3
            cases[(task, label)][i] = max(cases[(task, label)][i], float(m.group(2)))


def upper95(k, n):
    # Clopper-Pearson one-sided 95% upper bound, by bisection on the binomial tail.
    if n == 0:
        return float("nan")
    if k == 0:
        return 1 - 0.05 ** (1 / n)
    lo, hi = k / n, 1.0
    for _ in range(60):
        p = (lo + hi) / 2
        tail = sum(math.comb(n, i) * p**i * (1 - p) ** (n - i) for i in range(k + 1))
        lo, hi = (p, hi) if tail > 0.05 else (lo, p)
    return hi


print("| task | case | seeds | failures | 95% upper bound | max error ratio | max worst-tile \\|z\\| |")
print("|---|---|---|---|---|---|---|")
for (task, label), (k, n, ratio, z) in sorted(cases.items()):
    if label == "(the whole task)" and any(t == task and l != label for (t, l) in cases):
        continue
    print("| %s | %s | %d | %d | %.2g | %s | %s |" % (task, label, n, k, upper95(k, n),
          "%.3f" % ratio if ratio else "-", "%.2f" % z if z else "-"))
EOF
