#!/bin/sh
# Volpath efficiency 1/(CPU time x relMSE) of two subsurf binaries side by
# side (issue 14): each scene at RES x RES, a converged reference rendered by
# NEW, then RUNS alternating runs of OLD and NEW at SPP (one thread, seeds
# 1..RUNS), relMSE from `subsurf compare` over the translucent pixels, the
# render's CPU time = the process's CPU time minus the median set-up CPU time
# (the same command at 1 spp on one pixel). Prints medians per scene.
# usage: bench/volpath_efficiency.sh OLD NEW [RUNS=5] [SPP=64] [REF_SPP=1024] [RES=64]
set -eu
old=$1 new=$2 runs=${3:-5} spp=${4:-64} refspp=${5:-1024} res=${6:-64}
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
. "$root/bench/efficiency_lib.sh"
efficiency_header bin
for scene in skin_sphere skin_sphere_thick skin_sphere_matched; do
  sized "$root/scenes/$scene.json" "$res" >"$dir/$scene.json"
  nice "$new" render "$dir/$scene.json" -o "$dir/$scene-ref.exr" --spp "$refspp" --seed 999 \
    --quiet --no-png
  efficiency_pair "$scene" "$dir/$scene.json" "$dir/$scene-ref.exr" \
    old "$old" volpath "$dir/$scene.json" new "$new" volpath "$dir/$scene.json"
done
