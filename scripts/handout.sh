#!/usr/bin/env bash
# Writes the student handouts (assignments/partN/: stubs, README, grading
# manifest) at one of two levels of scaffolding (issue 21):
#   guided    today's handouts: each function's contract, the physics, the
#             references, and the steps of each algorithm (TODO step lists,
#             worked examples);
#   standard  the contract, the equations and the references only: every
#             block between the markers "// [guided]" and "// [/guided]"
#             (stubs) or "<!-- guided -->" and "<!-- /guided -->" (READMEs)
#             is replaced by one line saying that the steps are the student's.
# The grader judges both alike: no task needs a fixed order of random
# numbers (docs/handouts.md says why).
set -euo pipefail
usage() {
  cat <<'USAGE'
usage: scripts/handout.sh --level guided|standard OUT/
Copies assignments/part*/ (stubs, README.md, grading.json, deliverables.json) into OUT/
at the chosen level of scaffolding: guided (contracts, physics and the step lists) or
standard (contracts, equations and references; the step lists removed). OUT/ must not
exist or be empty. Build a handout with -DPT_STUDENT_DIR=OUT.
USAGE
}
level="" out=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --level) [ $# -ge 2 ] || { echo "handout: --level needs guided or standard" >&2; exit 2; }; level=$2; shift 2 ;;
    -*) echo "handout: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "handout: one output folder only, got '$out' and '$1'" >&2; exit 2; }; out=$1; shift ;;
  esac
done
case "$level" in
  guided|standard) ;;
  "") echo "handout: --level guided|standard is required (see --help)" >&2; exit 2 ;;
  *) echo "handout: --level: expected guided or standard, got '$level'" >&2; exit 2 ;;
esac
[ -n "$out" ] || { echo "handout: the output folder is missing (see --help)" >&2; exit 2; }
if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
  echo "handout: $out: exists and is not empty (refusing to overwrite)" >&2; exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
tmp="$(mktemp -d "${out%/}.tmp.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

# filter LEVEL OPEN CLOSE REPLACEMENT < in > out: keeps or drops the marked blocks.
filter() {
  awk -v level="$1" -v open_marker="$2" -v close_marker="$3" -v repl="$4" '
    { line = $0; sub(/^[ \t]+/, "", line) }
    line == open_marker { if (inside) { print "handout: nested marker at line " NR > "/dev/stderr"; exit 3 }
                    inside = 1; indent = $0; sub(/[^ \t].*$/, "", indent)
                    if (level == "standard") print indent repl; next }
    line == close_marker { if (!inside) { print "handout: unmatched end marker at line " NR > "/dev/stderr"; exit 3 }
                    inside = 0; next }
    inside && level == "standard" { next }
    { print }
    END { if (inside) { print "handout: marker not closed" > "/dev/stderr"; exit 3 } }'
}

for dir in "$root"/assignments/part*/; do
  part=$(basename "$dir")
  mkdir -p "$tmp/$part"
  for file in "$dir"*; do
    name=$(basename "$file")
    case "$name" in
      *.cpp|*.h) filter "$level" "// [guided]" "// [/guided]" \
                   "// (Standard handout: how to compute it is yours to work out from the contract and the README.)" \
                   < "$file" > "$tmp/$part/$name" || { echo "handout: $file: bad markers" >&2; exit 1; } ;;
      *.md) filter "$level" "<!-- guided -->" "<!-- /guided -->" \
              "*(Standard handout: the steps are yours to work out; the contract and the physics above are all you need.)*" \
              < "$file" > "$tmp/$part/$name" || { echo "handout: $file: bad markers" >&2; exit 1; } ;;
      *) cp "$file" "$tmp/$part/$name" ;;
    esac
  done
done
mkdir -p "$out"
cp -r "$tmp"/. "$out"/
echo "handout: wrote $out ($level: $(ls -d "$out"/part* | wc -l) parts)"
