#!/usr/bin/env bash
# make validate, second half (after `ctest -L slow`): regenerates the numbers
# and figures of docs/models.md into OUT_DIR, never into docs/.
# Usage: validate.sh BUILD_DIR OUT_DIR
#
# OUT_DIR/models_vs_halfspace.md       the dipole family against the reference
# OUT_DIR/pbd_tables_vs_halfspace.md   pbd, table-radial, table-gwc against it
# OUT_DIR/fwddip_vs_halfspace.md       fwddip and fwddip-brdf in Frederickx2017's set-ups
# OUT_DIR/aniso_fig10.md              aniso-dipole against micro-flake half-spaces
# OUT_DIR/fem_fig10.md                FEM and aniso-dipole against the flake cube, and the
#                                     FEM over the flakes' anisotropy and optical size (docs/fem.md)
# OUT_DIR/flake_diffusion_range.md    unbounded flake walks against the diffusion of M (docs/fem.md)
# OUT_DIR/plots/NAME.svg               the profile figures of docs/plots/
# OUT_DIR/NAME.json                    reference, models and errors of each figure
#
# docs/plots/ holds copies of OUT_DIR/plots/ (same commands, same seeds: the
# reference is bit-identical for any number of threads).
set -euo pipefail
build=${1:-build}
out=${2:-out/validate}

for exe in subsurf test_models_vs_halfspace test_pbd_tables_vs_halfspace test_fwddip_vs_halfspace \
  test_aniso_fig10 test_fem_fig10 test_flake_diffusion_range; do
  if [ ! -x "$build/$exe" ]; then
    echo "validate.sh: $build/$exe not found; run 'make build' first" >&2
    exit 2
  fi
done
mkdir -p "$out/plots"
start=$SECONDS

# The tables of docs/models.md: every grid point (2 x 10^5 reference paths
# each), with the regime assertions; a failed assertion fails the script.
table() {
  local test=$1 file=$2
  echo "== $file ($test)"
  SUBSURF_VALIDATE_OUT="$out/$file" "$build/$test" --jobs 1 >/dev/null 2>"$out/$test.log" || {
    cat "$out/$test.log" >&2
    echo "validate.sh: $test failed (log: $out/$test.log)" >&2
    exit 1
  }
  cat "$out/$file"
  echo
}
table test_models_vs_halfspace models_vs_halfspace.md
table test_pbd_tables_vs_halfspace pbd_tables_vs_halfspace.md
# The forward scattering dipole in Frederickx2017's Fig. 3/4 and Fig. 5 set-ups
# (docs/fwddip.md): its figures go to plots/fwddip_fig4.svg, fwddip_fig5.svg and
# the Fig. 3 exitance maps plots/fwddip_fig3_exitance_{0,45,80}.png.
rm -f "$out/fwddip_vs_halfspace.md" # the test appends its three tables
SUBSURF_VALIDATE_DIR="$out/plots" table test_fwddip_vs_halfspace fwddip_vs_halfspace.md
# Jakob et al. 2010's Fig. 10d-f: micro-flake half-spaces against aniso-dipole
# (docs/anisotropic.md; about 70 CPU seconds).
table test_aniso_fig10 aniso_fig10.md
# Jakob et al. 2010's Fig. 10a-c: the finite elements on the 4 cm flake cube
# against its Monte Carlo and aniso-dipole, then over the flakes' anisotropy
# and the cube's optical size (docs/fem.md; 344 s wall, 93 CPU s at load
# 10-13); the figure goes to plots/fem_fig10.svg.
rm -f "$out/fem_fig10.md" "$out/flake_diffusion_range.md" # the tests append their tables
SUBSURF_VALIDATE_DIR="$out/plots" table test_fem_fig10 fem_fig10.md
# Where the diffusion of M holds in an unbounded flake medium (docs/fem.md).
table test_flake_diffusion_range flake_diffusion_range.md

# The figures: the reference and models on identical bins.
plot() {
  local name=$1
  shift
  echo "== plots/$name.svg: subsurf compare-halfspace $*"
  "$build/subsurf" compare-halfspace "$@" --quiet \
    --plot "$out/plots/$name.svg" --json "$out/$name.json"
  echo
}
plot eta1.33_albedo0.99_theta0 \
  --models dipole,dipole+single,better-dipole,dirpole,single \
  --sigma-s 0.99 --sigma-a 0.01 --eta 1.33 --paths 400000 --seed 3 --rmin 0.02 --rmax 40 --rbins 48
plot eta1_albedo0.9_theta60 \
  --models dipole,dipole+single,better-dipole,dirpole,single \
  --sigma-s 0.9 --sigma-a 0.1 --eta 1 --theta-i 60 --paths 400000 --seed 3 --rmin 0.02 --rmax 20 \
  --rbins 48
plot pbd_eta1.33_albedo0.99_theta60 \
  --models pbd,table-radial,table-gwc+single,dipole+single \
  --sigma-s 0.99 --sigma-a 0.01 --eta 1.33 --theta-i 60 --paths 400000 --seed 3 --rmin 0.02 \
  --rmax 40 --rbins 48
plot pbd_eta1_albedo0.99_theta60 \
  --models pbd,table-radial,dipole+single \
  --sigma-s 0.99 --sigma-a 0.01 --eta 1 --theta-i 60 --paths 400000 --seed 3 --rmin 0.02 \
  --rmax 40 --rbins 48
plot pbd_eta1.33_albedo0.5_theta0 \
  --models pbd,table-radial,table-gwc+single,dipole+single \
  --sigma-s 0.5 --sigma-a 0.5 --eta 1.33 --paths 400000 --seed 3 --rmin 0.02 --rmax 10 --rbins 40

# Yarn and wood (docs/anisotropic.md): volpath and aniso-dipole
# side by side: OUT_DIR/aniso_scenes.md, OUT_DIR/aniso_scenes/.
bash "$(dirname "$0")/validate_aniso_scenes.sh" "$build" "$out"
# The papers' figures with `subsurf compare` (docs/results.md "The papers'
# figures"): OUT_DIR/figures/.
bash "$(dirname "$0")/validate_figures.sh" "$build" "$out"
# The hybrid's and the hierarchical integrator's papers (docs/results.md
# "Hierarchical and hybrid"): OUT_DIR/hybrid_hierarchical/.
bash "$(dirname "$0")/validate_hybrid_hierarchical.sh" "$build" "$out"
# Jakob2010's Fig. 9a-like render, fem against volpath (docs/fem.md):
# OUT_DIR/fem/.
bash "$(dirname "$0")/validate_fem.sh" "$build" "$out"

echo "validate.sh: done in $((SECONDS - start)) s; tables, figures and JSON in $out/"
