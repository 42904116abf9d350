#!/usr/bin/env bash
# The BSSRDF-versus-volpath comparison of docs/results.md: every
# model rendered by the bssrdf integrator on scenes/skin_sphere_thick.json,
# skin_sphere.json and skin_sphere_matched.json against volpath. About 30
# minutes on 2 cores; not part of make validate.
# Usage: bssrdf_accuracy.sh BUILD_DIR OUT_DIR [WIDTH REF_SPP SPP]
set -euo pipefail
build=${1:-build}
out=${2:-out/accuracy}
width=${3:-96}
ref_spp=${4:-256}
spp=${5:-64}
if [ ! -x "$build/bench_subsurface" ]; then
  echo "bssrdf_accuracy.sh: $build/bench_subsurface not found; run 'make build' first" >&2
  exit 2
fi
mkdir -p "$out"
models="dipole dipole+single better-dipole better-dipole+single dirpole dirpole+single multipole
  pbd table-radial table-gwc dipole-brdf single layers fwddip fwddip-brdf volpath"
for scene in skin_sphere_thick skin_sphere skin_sphere_matched; do
  echo "== $scene ($width px, volpath $ref_spp spp, models $spp spp)"
  # shellcheck disable=SC2086
  "$build/bench_subsurface" "scenes/$scene.json" sphere "$width" "$ref_spp" "$spp" $models |
    tee "$out/$scene.txt"
  echo
done
