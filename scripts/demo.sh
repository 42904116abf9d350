#!/usr/bin/env bash
# make demo: the main job on the bundled default. Usage: demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out/demo"
echo "subsurf demo: exact Monte Carlo reference for a beam entering Skin1 (Jensen et al. 2001),"
echo "              red, green and blue, eta 1.3, 10^6 paths per channel"
"$build/subsurf" halfspace --medium Skin1 --channel rgb --paths 1e6 \
  --xmin -8 --xmax 8 --ymin -8 --ymax 8 --xbins 256 --ybins 256 --rmax 20 \
  --theta-o 0 --theta-o 60 \
  --map "$out/demo/skin1_exitance.exr" --map "$out/demo/skin1_exitance.png" \
  --json "$out/demo/skin1_halfspace.json"
echo
echo "results:"
echo "  $out/demo/skin1_exitance.exr   exitance map, linear float, per unit incident power (mm^-2)"
echo "  $out/demo/skin1_exitance.png   the same map, tonemapped"
echo "  $out/demo/skin1_halfspace.json reflectance, radial profile and radiance slices with errors"
