#!/bin/sh
# Volpath's efficiency 1/(CPU time x relMSE) with manifold next-event
# estimation off and on, side by side in one run: each scene at
# RES x RES, a converged reference (mnee on, REF_SPP, two threads), then RUNS
# alternating runs of `volpath:mnee=0` and `volpath:mnee=1` at SPP (one
# thread, seeds 1..RUNS); with MNEE_BEFORE=every the first of the pair is
# instead MNEE toward every light at every vertex
# (`volpath:mnee=1:mnee_solid_angle=100`, volpath before the rate toward
# area lights), relMSE from `subsurf compare` over the translucent
# pixels, the render's CPU time = the process's CPU time minus the median
# set-up CPU time (the same command at 1 spp on one pixel). Scenes:
# skin_sphere (lamp of radius 2), the same with a lamp of radius 0.05 and the
# same power (skin_sphere_small), skin_sphere_point (the point-light
# limit: without MNEE its medium stays black, relMSE 1), skin_sphere_thick
# (radius 5, not in the default list: its renders take the longest), and the nested
# skin_flesh_sphere, whose flesh core reaches the lamp through a chain of
# two refractions (skin_in_glass.json cannot be measured so: `compare`
# needs translucent pixels, and the camera sees its glass).
# MNEE_SCENES (space-separated) picks some of them. Prints medians; with
# $EFFICIENCY_LOG set every run (per channel) goes to that file, and with
# $REFS set the references are kept in (and read back from) that directory
# as SCENE-RES-REF_SPP.exr.
# usage: bench/mnee_efficiency.sh SUBSURF [RUNS=5] [SPP=32] [REF_SPP=512] [RES=32]
set -eu
bin=$1 runs=${2:-5} spp=${3:-32} refspp=${4:-512} res=${5:-32}
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
. "$root/bench/efficiency_lib.sh"
sized "$root/scenes/skin_sphere.json" "$res" >"$dir/skin_sphere.json"
sized "$root/scenes/skin_sphere_point.json" "$res" >"$dir/skin_sphere_point.json"
# radiance x (2 / 0.05)^2: the same power from a sphere of radius 0.05
sized "$root/scenes/skin_sphere.json" "$res" |
  sed -e 's/"radius": 2, "center"/"radius": 0.05, "center"/' -e 's/"radiance": 10 }/"radiance": 16000 }/' \
    >"$dir/skin_sphere_small.json"
sized "$root/scenes/skin_flesh_sphere.json" "$res" >"$dir/skin_flesh_sphere.json"
sized "$root/scenes/skin_sphere_thick.json" "$res" >"$dir/skin_sphere_thick.json"
before=0 beforeopt=mnee=0
if [ "${MNEE_BEFORE:-}" = every ]; then
  before=every beforeopt=mnee=1:mnee_solid_angle=100
fi
efficiency_header mnee
for scene in ${MNEE_SCENES:-skin_sphere skin_sphere_small skin_sphere_point skin_flesh_sphere}; do
  ref=${REFS:-$dir}/$scene-$res-$refspp.exr
  if [ ! -f "$ref" ]; then
    nice "$bin" render "$dir/$scene.json" -o "$ref" --spp "$refspp" --seed 999 \
      --quiet --no-png --threads 2
  fi
  for m in 0 1; do
    sed "s/\"integrator\": *{ *\"type\": \"volpath\"/\"integrator\": { \"type\": \"volpath\", \"mnee\": $m/" \
      "$dir/$scene.json" | sed 's/"mnee": \([01]\), "mnee": [01]/"mnee": \1/' >"$dir/setup$m.json"
  done
  efficiency_pair "$scene" "$dir/$scene.json" "$ref" \
    "$before" "$bin" "volpath:$beforeopt" "$dir/setup$([ $before = 0 ] && echo 0 || echo 1).json" \
    1 "$bin" volpath:mnee=1 "$dir/setup1.json"
done
