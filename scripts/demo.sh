#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders
# the demo scene to out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
# Path-traced Cornell box with a mirror and a glass sphere: 5 bounces,
# 256 samples per pixel (about 7 s on 2 cores).
build/bin/pathtracer -t "$(nproc)" -r 320 240 -s 256 -m 5 -f out/demo.png assets/scenes/cbox_spheres.json
echo "demo: wrote out/demo.png"
