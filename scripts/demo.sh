#!/usr/bin/env bash
# make demo: the main job on the bundled defaults. Usage: demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out/demo"

echo "subsurf demo 1/2: volumetric path tracing (the ground truth) of scenes/skin_rough_sphere.json,"
echo "                  a Skin1 sphere behind a rough dielectric boundary, 160 samples per pixel"
"$build/subsurf" render scenes/skin_rough_sphere.json --spp 160 --time-limit 100 \
  -o "$out/demo/skin_rough_sphere.exr"

echo
echo "subsurf demo 2/2: the exact half-space reference for a beam entering Skin1,"
echo "                  red, green and blue, eta 1.3, 10^6 paths per channel"
"$build/subsurf" halfspace --medium Skin1 --channel rgb --paths 1e6 \
  --xmin -8 --xmax 8 --ymin -8 --ymax 8 --xbins 256 --ybins 256 --rmax 20 \
  --theta-o 0 --theta-o 60 \
  --map "$out/demo/skin1_exitance.exr" --map "$out/demo/skin1_exitance.png" \
  --json "$out/demo/skin1_halfspace.json"

echo
echo "results:"
echo "  $out/demo/skin_rough_sphere.exr  rendered image, linear float"
echo "  $out/demo/skin_rough_sphere.png  the same, tonemapped"
echo "  $out/demo/skin1_exitance.exr     half-space exitance map per unit incident power (mm^-2)"
echo "  $out/demo/skin1_exitance.png     the same map, tonemapped"
echo "  $out/demo/skin1_halfspace.json   reflectance, radial profile and radiance slices with errors"
