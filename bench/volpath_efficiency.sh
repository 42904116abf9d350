#!/bin/sh
# Volpath efficiency 1/(CPU time x relMSE) of two subsurf binaries side by
# side: each scene at RES x RES, a converged reference rendered by
# NEW (REF_SPP, two threads), then RUNS alternating runs of OLD and NEW at SPP
# (one thread, seeds 1..RUNS), relMSE from `subsurf compare` over the
# translucent pixels, the render's CPU time = the process's CPU time minus
# the median set-up CPU time (the same command at 1 spp on one pixel,
# measured in the same run). The index-matched sphere, whose samples cost
# several times less, runs at MATCHED x SPP and MATCHED x REF_SPP so that
# each of its renders also takes seconds of CPU. Prints medians per scene,
# then each binary's rays/s and scattering events/s (its own statistics of
# one render at SPP, one thread). Every run goes to $EFFICIENCY_LOG when set;
# with $REFS set, the references are kept in (and read back from) that
# directory as SCENE-RES-REF_SPP.exr.
# usage: bench/volpath_efficiency.sh OLD NEW [RUNS=5] [SPP=64] [REF_SPP=1024] [RES=64] [MATCHED=4]
set -eu
old=$1 new=$2 runs=${3:-5} spp0=${4:-64} refspp0=${5:-1024} res=${6:-64} matched=${7:-4}
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
. "$root/bench/efficiency_lib.sh"
scenes="skin_sphere skin_sphere_thick skin_sphere_matched"
efficiency_header bin
for scene in $scenes; do
  spp=$spp0 refspp=$refspp0
  if [ "$scene" = skin_sphere_matched ]; then
    spp=$((spp0 * matched)) refspp=$((refspp0 * matched))
  fi
  sized "$root/scenes/$scene.json" "$res" >"$dir/$scene.json"
  ref=${REFS:-$dir}/$scene-$res-$refspp.exr
  if [ ! -f "$ref" ]; then
    nice "$new" render "$dir/$scene.json" -o "$ref" --spp "$refspp" --seed 999 \
      --threads 2 --quiet --no-png
  fi
  efficiency_pair "$scene" "$dir/$scene.json" "$ref" \
    old "$old" volpath "$dir/$scene.json" new "$new" volpath "$dir/$scene.json"
done
printf '%-20s %-6s %12s %12s\n' scene bin rays/s events/s
for scene in $scenes; do
  spp=$spp0
  if [ "$scene" = skin_sphere_matched ]; then
    spp=$((spp0 * matched))
  fi
  for v in old new; do
    if [ $v = old ]; then vbin=$old; else vbin=$new; fi
    "$vbin" render "$dir/$scene.json" -o "$dir/rate.exr" --spp "$spp" --threads 1 --no-png \
      2>&1 | sed -n 's/.* \([0-9.e+]*\) rays\/s, \([0-9.e+]*\) scattering events\/s.*/\1 \2/p' |
      awk -v n="$scene" -v l="$v" '{printf "%-20s %-6s %12s %12s\n", n, l, $1, $2}'
  done
done
