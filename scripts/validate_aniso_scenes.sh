#!/usr/bin/env bash
# make validate (docs/anisotropic.md "Yarn and wood: volpath and
# the anisotropic dipole"): scenes/yarn.json and scenes/wood.json rendered by
# volpath (the reference, `subsurf compare`'s) and by the bssrdf integrator
# with aniso-dipole, side by side; the mean ratio over the pixels where the
# camera sees the translucent box.
# Usage: validate_aniso_scenes.sh BUILD_DIR OUT_DIR
# Writes OUT_DIR/aniso_scenes.md and OUT_DIR/aniso_scenes/{yarn,wood}/.
set -euo pipefail
build=${1:-build}
out=${2:-out/validate}
spp=${ANISO_SPP:-16}
ref_spp=${ANISO_REF_SPP:-64}
md=$out/aniso_scenes.md
mkdir -p "$out"
{
  echo "| scene | method | spp | mean ratio R | G | B | relMSE | s |"
  echo "|---|---|---|---|---|---|---|---|"
} >"$md"
for scene in yarn wood; do
  dir=$out/aniso_scenes/$scene
  mkdir -p "$dir"
  echo "== $scene: volpath (reference, $ref_spp spp) and aniso-dipole ($spp spp)"
  "$build/subsurf" compare "scenes/$scene.json" --methods volpath,aniso-dipole --spp "$spp" \
    --reference-spp "$ref_spp" -o "$dir" --quiet
  jq -r --arg s "$scene" '.methods[] | "| \($s) | \(.method) | \(.spp) | \(.mean_ratio_rgb | map(. * 1000 | round / 1000) | join(" | ")) | \(.rel_mse * 10000 | round / 10000) | \(.seconds * 100 | round / 100) |"' \
    "$dir/results.json" >>"$md"
done
cat "$md"
