#!/usr/bin/env bash
# Re-renders the README's images with the README's own commands and compares
# them byte for byte with docs/images/ (a render depends only on the scene,
# the flags and the seed, never on the thread count), so that an image that
# no longer matches the program is found. Exit 0 when all match, 1 when
# one drifted; --update copies the new renders over the old ones.
set -euo pipefail
case "${1:-}" in
  -h|--help)
    cat <<'USAGE'
usage: scripts/readme_images.sh [--update] [IMAGE...]
Re-renders the README's images (docs/images/NAME.png) with the commands the README gives,
into build/readme_images/, and compares them byte for byte with docs/images/. Prints
"same" or "DRIFT" per image; exit 0 when all are the same, 1 otherwise. IMAGE names
limit the run (e.g. demo.png whitted.png); --update copies drifted renders into docs/images/.
Not re-rendered: images that depend on timing (equal-time comparisons, accuracy plots),
on a converged reference (the -l sequence) or on other tools (the x2..x16 brightened
images, the grade report screenshot). About 4 CPU-minutes: 2 minutes on 2 idle cores.
USAGE
    exit 0 ;;
esac
cd "$(dirname "$0")/.."
update=0
if [ "${1:-}" = "--update" ]; then update=1; shift; fi
[ -x build/bin/pathtracer ] || { echo "readme_images: build/bin/pathtracer is missing; run scripts/build.sh" >&2; exit 2; }
out=build/readme_images
mkdir -p "$out"
threads=$(nproc)

# NAME|pathtracer arguments (as in the README and docs/global.md), scene last.
images=(
  "demo.png|-r 320 240 -s 256 -m 5 assets/scenes/cbox_spheres.json"
  "media_fog.png|-r 200 200 -s 64 -m 8 assets/scenes/cbox_fog.json"
  "media_milk.png|-r 200 200 -s 64 -m 32 assets/scenes/cbox_milk.json"
  "media_cloud.png|-r 256 144 -s 32 -m 16 assets/scenes/cloud.json"
  "materials.png|-r 384 192 -s 256 -l 4 -m 8 assets/scenes/materials.json"
  "materials_dof.png|-r 384 192 -s 256 -l 4 -m 8 -b 0.08 -d 4.2 assets/scenes/materials.json"
  "whitted.png|-r 320 240 -s 16 assets/scenes/whitted.json"
  "whitted_path.png|-r 320 240 -s 256 -m 8 --integrator path assets/scenes/whitted.json"
  "adaptive_cbox.png|-r 256 256 -s 1024 -a 32 0.05 assets/scenes/cbox.json"
  "glossy.png|-r 640 256 -s 64 -m 8 assets/scenes/glossy.json"
  "textures.png|-r 512 256 -s 64 -m 4 assets/scenes/textures.json"
  "csg.png|-r 512 256 -s 64 -m 6 assets/scenes/csg.json"
  "groups.png|-r 512 256 -s 32 -m 4 assets/scenes/groups.json"
  "camera_orthographic.png|-r 256 256 -s 64 -m 4 assets/scenes/camera_orthographic.json"
  "camera_fisheye.png|-r 256 256 -s 64 -m 4 assets/scenes/camera_fisheye.json"
  "mirror_pm.png|-r 200 150 -s 16 --integrator pm assets/scenes/caustic_mirror.json"
  "mirror_path.png|-r 200 150 -s 64 -m 100000 --integrator path assets/scenes/caustic_mirror.json"
  "mirror_caustic_map.png|-r 200 150 -s 4 --photon-view caustic assets/scenes/caustic_mirror.json"
  "bulb_pm.png|-r 200 150 -s 16 --integrator pm assets/scenes/light_bulb.json"
)
for m in 0 1 2 3 4 5; do
  images+=("cbox_m${m}_o1.png|-r 128 128 -s 256 -m $m assets/scenes/cbox.json")
  images+=("cbox_m${m}_o0.png|-r 128 128 -s 256 -m $m -o 0 assets/scenes/cbox.json")
done
for rr in off 3 1 0; do
  images+=("cbox_rr_${rr}.png|-r 128 128 -s 64 -m 100000 --rr-depth $rr assets/scenes/cbox.json")
done
for t in clamp reinhard filmic local; do
  images+=("tonemap_$t.png|-r 256 128 -s 64 -m 8 --exposure 1 --tonemap $t assets/scenes/materials.json")
done

wanted() {
  [ $# -eq 0 ] && return 0
  local w
  for w in "$@"; do [ "$w" = "$NAME" ] && return 0; done
  return 1
}

drift=0
checked=0
for entry in "${images[@]}"; do
  NAME=${entry%%|*}
  args=${entry#*|}
  wanted "$@" || continue
  checked=$((checked + 1))
  # shellcheck disable=SC2086  # the arguments are words on purpose
  build/bin/pathtracer -q -t "$threads" $args -f "$out/$NAME" > "$out/${NAME%.png}.log"
  compare=("$NAME")
  [[ $args == *" -a "* ]] && compare+=("${NAME%.png}_rate.png")
  for image in "${compare[@]}"; do
    if cmp -s "$out/$image" "docs/images/$image"; then
      echo "same   $image"
    else
      echo "DRIFT  $image  (pathtracer $args; new render in $out/$image)"
      drift=1
      [ "$update" = 1 ] && cp "$out/$image" "docs/images/$image" && echo "       updated docs/images/$image"
    fi
  done
done
[ "$checked" -gt 0 ] || { echo "readme_images: no image named $*" >&2; exit 2; }
if [ "$drift" = 1 ] && [ "$update" = 0 ]; then
  echo "readme_images: some images no longer match the program; rerun with --update to replace them" >&2
  exit 1
fi
echo "readme_images: $checked renders checked"
