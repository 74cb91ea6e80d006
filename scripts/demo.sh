#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders
# the demo scene to out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/bin/pathtracer -t "$(nproc)" -r 320 240 -f out/demo.png assets/scenes/cbox_spheres.json
echo "demo: wrote out/demo.png"
