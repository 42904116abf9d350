#!/usr/bin/env bash
# make demo: what subsurf is for, on the bundled defaults. Usage: demo.sh BUILD_DIR OUT_DIR
# The thick Skin1 sphere (scenes/demo_skin_sphere.json: skin_sphere_thick.json
# at 96 x 96), where the BSSRDF models are right (docs/results.md: pbd within
# 5 % of volpath per channel), rendered by pbd and by volpath with the same
# wall time, against a longer volpath reference; every budget is wall time,
# so the demo takes about two minutes whatever the machine (a slower or busier
# one gets fewer samples).
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out/demo"

echo "subsurf demo: the best BSSRDF model (pbd) against volumetric path tracing (volpath),"
echo "              20 s each, on a Skin1 x 50 sphere; reference: volpath for 60 s"
"$build/subsurf" compare scenes/demo_skin_sphere.json --methods pbd,volpath --time 20 \
  --reference-time 60 -o "$out/demo/compare"

echo
echo "results:"
echo "  $out/demo/compare/index.html    the report: open it in a browser (works offline)"
echo "  $out/demo/compare/results.json  relMSE, mean ratio per channel, times, error curves"
echo "  $out/demo/compare/pbd.png       the BSSRDF image; volpath.png, reference.png beside it"
echo
echo "put the command on PATH for the README's examples:  export PATH=\"$PWD/$build:\$PATH\""
