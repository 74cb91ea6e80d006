#!/bin/sh
# The engine archive of the grading runners (src/CMakeLists.txt): every
# object of the engine, with the reference functions it DEFINES made weak,
# so that a runner's throwing stand-ins (src/grade/runner/withheld.cpp)
# replace them. References to them stay strong, so the linker still pulls
# the objects that define them. Besides pt::reference, the engine helpers
# that compute a graded answer whole are weakened too (a student could
# call them instead of writing the task): sample_lights_mis is task 3.5's
# estimator, bsdf_sample_mis_weight half of task 3.8's.
#   weaken_reference.sh OUT.a OBJECT...
set -e
out=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
i=0
for o in "$@"; do
  i=$((i + 1))
  copy="$tmp/$i-$(basename "$o")"
  cp "$o" "$copy"
  nm --defined-only "$copy" | awk '($3 ~ /^_ZN2pt9reference/ || $3 ~ /^_ZN2pt17sample_lights_mis/ || $3 ~ /^_ZN2pt22bsdf_sample_mis_weight/) && ($2 == "T" || $2 == "W") { print $3 }' > "$tmp/symbols"
  if [ -s "$tmp/symbols" ]; then objcopy --weaken-symbols="$tmp/symbols" "$copy"; fi
done
rm -f "$out.tmp"
ar rcs "$out.tmp" "$tmp"/*.o
mv "$out.tmp" "$out"
