#!/usr/bin/env bash
# Writes a scene of N x N instances of one shape (README "Instancing"):
# the Stanford bunny from ../shared/meshes when it is there, else the
# generated 10,000-triangle torus knot, on a grey floor under the sky, each
# instance turned and scaled by a fixed pseudo-random sequence.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/instances_scene.sh N OUT.json [--knot | --mesh FILE.obj]
Writes OUT.json with N x N instances (N = 100: 10,000) of the Stanford bunny
(../shared/meshes/stanford-bunny.obj next to the repository, absolute path in OUT.json)
or of FILE.obj (--mesh), or, with --knot or without the bunny, of a generated
10,000-triangle torus knot.
Render it with build/bin/pathtracer OUT.json; `--stats FILE` reports the accelerator's
bytes, `/usr/bin/time -v` the peak memory (README "Instancing").
USAGE
    exit 0 ;;
esac
[ $# -ge 2 ] || { echo "instances_scene: usage: scripts/instances_scene.sh N OUT.json [--knot | --mesh FILE.obj]" >&2; exit 2; }
n=$1 out=$2
[[ "$n" =~ ^[1-9][0-9]{0,3}$ ]] || { echo "instances_scene: N: expected a whole number from 1 to 9999, got '$n'" >&2; exit 2; }
root="$(cd "$(dirname "$0")/.." && pwd)"
bunny="$(cd "$root/.." && pwd)/shared/meshes/stanford-bunny.obj"
if [ "${3:-}" = "--mesh" ]; then
  bunny="$(cd "$(dirname "${4:?--mesh needs a file}")" && pwd)/$(basename "$4")"
  [ -r "$bunny" ] || { echo "instances_scene: --mesh: cannot read $4" >&2; exit 2; }
fi
if [ "${3:-}" != "--knot" ] && [ -r "$bunny" ]; then
  shape="{\"type\": \"mesh\", \"file\": \"$bunny\"}"
  size=0.16 lift=-0.1   # the bunny is about 0.16 units across and sits at y = 0.03 (its OBJ units)
else
  shape='{"type": "torus_knot", "radius": 1, "tube_radius": 0.15, "segments": 500, "sides": 10}'
  size=2.6 lift=0.3   # the knot is about 2.6 units across, centred on the origin
fi
tmp="$out.tmp.$$"
awk -v n="$n" -v shape="$shape" -v size="$size" -v lift="$lift" 'BEGIN {
  spacing = 1.0; half = (n - 1) * spacing / 2; s = 1.0 / size * 0.6;
  printf "{\n  \"description\": \"%d x %d instances of one shape (scripts/instances_scene.sh)\",\n", n, n;
  printf "  \"camera\": {\"position\": [%g, %g, %g], \"look_at\": [0, 0, 0], \"vfov\": 40},\n", 0, 0.35 * n + 2, 0.9 * n + 3;
  printf "  \"film\": {\"width\": 640, \"height\": 360},\n";
  printf "  \"materials\": {\"floor\": {\"type\": \"diffuse\", \"albedo\": [0.5, 0.5, 0.5]},\n";
  printf "    \"a\": {\"type\": \"diffuse\", \"albedo\": [0.8, 0.5, 0.3]}, \"b\": {\"type\": \"diffuse\", \"albedo\": [0.3, 0.5, 0.8]}},\n";
  printf "  \"shapes\": {\"s\": %s},\n", shape;
  printf "  \"objects\": [\n    {\"type\": \"quad\", \"corner\": [%g, 0, %g], \"edge1\": [0, 0, %g], \"edge2\": [%g, 0, 0], \"material\": \"floor\"}", -half - 2, -half - 2, 2 * half + 4, 2 * half + 4;
  seed = 12345;
  for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
    seed = (seed * 1103515245 + 12345) % 2147483648; angle = seed % 360;
    seed = (seed * 1103515245 + 12345) % 2147483648; k = s * (0.7 + 0.6 * (seed % 1000) / 1000);
    printf ",\n    {\"type\": \"instance\", \"shape\": \"s\", \"material\": \"%s\", \"transform\": {\"scale\": %.4g, \"rotate\": [0, 1, 0, %d], \"translate\": [%g, %g, %g]}}", ((i + j) % 2 ? "a" : "b"), k, angle, i * spacing - half, lift * k * size / 0.6, j * spacing - half;
  }
  printf "\n  ],\n  \"lights\": [{\"type\": \"environment\", \"radiance\": [0.6, 0.7, 0.9]}, {\"type\": \"directional\", \"direction\": [-1, -2, -1], \"irradiance\": [2, 1.8, 1.5]}]\n}\n";
}' > "$tmp"
mv "$tmp" "$out"
echo "instances_scene: wrote $out ($((n * n)) instances)"
