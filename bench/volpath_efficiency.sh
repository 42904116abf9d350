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
printf '%-20s %-4s %10s %10s %12s %12s %10s\n' scene bin setup_cpu render_cpu relMSE efficiency ratio
for scene in skin_sphere skin_sphere_thick skin_sphere_matched; do
  sed "s/\"resolution\": \[256, 256\]/\"resolution\": [$res, $res]/" \
    "$root/scenes/$scene.json" >"$dir/$scene.json"
  nice "$new" render "$dir/$scene.json" -o "$dir/$scene-ref.exr" --spp "$refspp" --seed 999 \
    --quiet --no-png
  for b in old new; do
    bin=$old; [ $b = new ] && bin=$new
    for r in $(seq "$runs"); do
      cpu "$bin" render "$dir/$scene.json" -o "$dir/s.exr" --spp 1 --crop 0,0,1,1 --threads 1 \
        --quiet --no-png
    done | median >"$dir/setup-$b"
  done
  for r in $(seq "$runs"); do
    for b in old new; do
      bin=$old; [ $b = new ] && bin=$new
      t=$(cpu "$bin" compare "$dir/$scene.json" --methods volpath --spp "$spp" \
        --reference "$dir/$scene-ref.exr" --threads 1 --seed "$r" --quiet -o "$dir/$b")
      e=$(awk -F, 'NR == 2 {print $5}' "$dir/$b/results.csv")
      echo "$t $e" >>"$dir/runs-$b"
    done
  done
  for b in old new; do
    s=$(cat "$dir/setup-$b")
    awk -v s="$s" '{t = $1 - s; print t, $2, 1 / (t * $2)}' "$dir/runs-$b" >"$dir/eff-$b"
    t=$(awk '{print $1}' "$dir/eff-$b" | median)
    e=$(awk '{print $2}' "$dir/eff-$b" | median)
    f=$(awk '{print $3}' "$dir/eff-$b" | median)
    echo "$f" >"$dir/med-$b"
    ratio=$(awk -v a="$f" -v b="$(cat "$dir/med-old")" 'BEGIN {printf "%.2f", a / b}')
    printf '%-20s %-4s %10.3f %10.3f %12.4g %12.4g %10s\n' "$scene" "$b" "$s" "$t" "$e" "$f" "$ratio"
  done
  rm -f "$dir"/runs-* "$dir"/eff-*
done
