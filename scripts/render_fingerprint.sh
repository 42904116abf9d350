#!/usr/bin/env bash
# The bytes of every bundled scene rendered by each integrator that accepts
# it (fixed seed, 1 spp), of a few variants that switch on the integrators'
# other branches, and of `subsurf halfspace` / `subsurf model` JSON on a set
# of inputs: one "sha256  name" line per output, written to MANIFEST. Run it
# before and after a change that must move nothing, and diff the manifests.
#
#   scripts/render_fingerprint.sh MANIFEST   (SUBSURF=path/to/subsurf, default build/subsurf)
#
# An integrator that refuses a scene (exit 2 when its check refuses, 1 when
# its preparation does) is recorded as "refused-N", so a change in what is
# accepted shows too. The `fem` integrator solves a mesh
# per translucent object (about a minute each), so it renders only the
# scenes written for it. JSON outputs drop their "seconds" line, the only
# thing that differs between two identical runs.
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 MANIFEST" >&2
  exit 2
fi
manifest=$1
root=$(cd "$(dirname "$0")/.." && pwd)
subsurf=${SUBSURF:-$root/build/subsurf}
threads=${THREADS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
: >"$work/manifest"

# record NAME CMD...: runs CMD, which writes $work/out, and appends its hash.
record() {
  local name=$1
  shift
  rm -f "$work/out"
  local rc=0
  "$@" >"$work/log" 2>&1 || rc=$?
  if [ $rc -eq 1 ] || [ $rc -eq 2 ]; then
    echo "refused-$rc  $name" >>"$work/manifest"
  elif [ $rc -ne 0 ] || [ ! -s "$work/out" ]; then
    echo "$name failed (exit $rc):" >&2
    cat "$work/log" >&2
    exit 1
  else
    echo "$(sha256sum <"$work/out" | cut -d' ' -f1)  $name" >>"$work/manifest"
  fi
  echo "$name" >&2
}

render() {
  "$subsurf" render "$1" --integrator "$2" --spp 1 --seed 7 --threads "$threads" --quiet \
    --no-png -o "$work/out.exr" || return
  mv "$work/out.exr" "$work/out"
}

json() {
  "$subsurf" "$@" --json "$work/out.json" --quiet --threads 1 || return
  grep -v '"seconds":' "$work/out.json" >"$work/out"
}

json_model() {
  "$subsurf" model "$@" --json "$work/out.json" || return
  grep -v '"seconds":' "$work/out.json" >"$work/out"
}

# variant SCENE NAME PYTHON: a copy of SCENE edited by a Python statement on `d`.
variant() {
  python3 - "$1" "$work/$2.json" "$3" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
EOF
  echo "$work/$2.json"
}

integrators="path volpath bssrdf hierarchical hybrid"
for scene in "$root"/scenes/*.json; do
  base=$(basename "$scene" .json)
  type=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["integrator"]["type"])' "$scene")
  for i in $integrators; do
    record "$base/$i" render "$scene" "$i"
  done
  if [ "$type" = fem ]; then
    record "$base/fem" render "$scene" fem
  fi
done

# The integrators' options and levels of detail the bundled scenes leave at
# their defaults.
skin=$root/scenes/skin_sphere.json
point=$root/scenes/skin_sphere_point.json
# (An option is checked against the scene's own integrator type.)
record "variant/hybrid-depth0" render "$(variant "$skin" h0 'd["integrator"] = {"type": "hybrid", "depth": 0}')" hybrid
record "variant/hybrid-depth1" render "$(variant "$skin" h1 'd["integrator"] = {"type": "hybrid", "depth": 1}')" hybrid
record "variant/volpath-guide0" render "$(variant "$point" g0 'd["integrator"]["guide"] = 0')" volpath
record "variant/volpath-mnee" render "$(variant "$skin" mn 'd["integrator"]["mnee"] = 1')" volpath
record "variant/bssrdf-one-hit" render "$(variant "$skin" a0 'd["integrator"] = {"type": "bssrdf", "all_hits": 0}')" bssrdf
for lod in volpath brdf; do
  v=$(variant "$skin" "lod-$lod" "d['materials'][0]['lod'] = '$lod'")
  for i in bssrdf hierarchical; do
    record "variant/lod-$lod/$i" render "$v" "$i"
  done
done
v=$(variant "$skin" single 'd["materials"][0]["bssrdf"] = "single"')
record "variant/single/bssrdf" render "$v" bssrdf
v=$(variant "$skin" fwddip 'd["materials"][0]["bssrdf"] = "fwddip"')
record "variant/fwddip/bssrdf" render "$v" bssrdf

for args in "--sigma-s 1 --sigma-a 0.01" "--sigma-s 2 --sigma-a 0.1 --g 0.8 --phase hg --eta 1.4" \
  "--medium skin1 --channel rgb --eta 1.3 --theta-i 40 --theta-o 10" \
  "--sigma-s 1 --sigma-a 0.05 --thickness 2 --eta 1.5" "--flakes surface --sigma-s 1 --sigma-a 0.1"; do
  # shellcheck disable=SC2086
  record "halfspace $args" json halfspace $args --paths 20000 --seed 3 --rbins 16 --xbins 8 --ybins 8
done
for model in dipole better-dipole dirpole pbd multipole single burley; do
  for args in "--sigma-s 1 --sigma-a 0.01 --eta 1.3" "--medium skin1 --channel g --theta-i 30"; do
    # shellcheck disable=SC2086
    record "model $model $args" json_model --model "$model" $args --rbins 16 --xbins 8 --ybins 8
  done
done

mv "$work/manifest" "$manifest"
echo "$(grep -vc '^refused' "$manifest") outputs, $(grep -c '^refused' "$manifest") refusals: $manifest" >&2
