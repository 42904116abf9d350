#!/usr/bin/env bash
# make validate, Jakob2010's Fig. 9a-like render,
# called by validate.sh: scenes/fig9a_fem.json (a sphere of the procedural
# wood grid with fibre-like micro-flakes behind an index-matched boundary,
# lit by a 3 x 3 grid of spot lights) rendered by the `fem` integrator and
# by volpath side by side (`subsurf compare`: volpath's reference at REF_SPP,
# both methods at SPP), with the mean radiance of each against the reference
# per channel; then `fem` with the volume source (volume_source 1), and
# both sources with the material's single_scattering on (the tracked single
# scattering of grids and flakes, docs/fem.md), against the same reference.
# Usage: validate_fem.sh BUILD_DIR OUT_DIR
# Writes OUT_DIR/fem/fig9a.md and the compare folder OUT_DIR/fem/fig9a/
# (fem.png, volpath.png, reference.png, error images, index.html), and
# OUT_DIR/fem/fig9a_volume/ (the volume source's), fig9a_single/ and
# fig9a_volume_single/ (with single scattering).
set -euo pipefail
build=${1:-build}
out=${2:-out/validate}/fem
subsurf=$build/subsurf
spp=${SPP:-16}
ref_spp=${REF_SPP:-256}
mkdir -p "$out"
echo "== Jakob2010 Fig. 9a-like render, fem against volpath"
"$subsurf" compare scenes/fig9a_fem.json --methods fem,volpath --spp "$spp" \
  --reference-spp "$ref_spp" -o "$out/fig9a" --quiet
jq '.integrator.volume_source = 1' scenes/fig9a_fem.json >"$out/fig9a_volume.json"
jq '.materials[0].single_scattering = true' scenes/fig9a_fem.json >"$out/fig9a_single.json"
jq '.materials[0].single_scattering = true' "$out/fig9a_volume.json" >"$out/fig9a_volume_single.json"
for run in fig9a_volume fig9a_single fig9a_volume_single; do
  "$subsurf" compare "$out/$run.json" --methods fem --spp "$spp" \
    --reference "$out/fig9a/reference.exr" -o "$out/$run" --quiet
done
{
  echo "### Fig. 9a-like: wood sphere under a grid of spots (scenes/fig9a_fem.json)"
  echo
  echo "| method | mean / volpath reference (R, G, B) | relMSE | seconds |"
  echo "|---|---|---|---|"
  for run in fig9a fig9a_volume fig9a_single fig9a_volume_single; do
    jq -r --arg run "$run" '.methods[] | "| \(.method)\(if ($run | test("volume")) then ", volume_source 1" else "" end)\(if ($run | test("single")) then ", single_scattering" else "" end) | \(.mean_ratio_rgb | map(. * 1000 | round / 1000) | join(", ")) | \(.rel_mse * 1000 | round / 1000) | \(.seconds * 10 | round / 10) |"' \
      "$out/$run/results.json"
  done
} >"$out/fig9a.md"
cat "$out/fig9a.md"
