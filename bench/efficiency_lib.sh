# Helpers of the efficiency scripts (sourced; the caller sets $dir, a
# scratch directory, and $runs and $spp).
cpu() { # prints the CPU seconds (user + sys) of the command
  /usr/bin/time -f "%U %S" -o "$dir/time" "$@" >/dev/null 2>&1
  awk '{print $1 + $2}' "$dir/time"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# sized SCENE RES: the scene file at RES x RES pixels (same camera and geometry)
sized() { sed "s/\"resolution\": \[256, 256\]/\"resolution\": [$2, $2]/" "$1"; }
# efficiency_header LABEL: the table's header; LABEL names the variant column
efficiency_header() {
  printf '%-20s %-6s %10s %10s %12s %12s %8s\n' scene "$1" setup_cpu render_cpu relMSE efficiency ratio
}
# efficiency_pair NAME SCENE REF  A BIN_A METHOD_A SETUP_A  B BIN_B METHOD_B SETUP_B
# Two variants (label, subsurf binary, compare method, scene file whose
# render at 1 spp on one pixel measures the variant's set-up) side by side:
# the median set-up CPU time of $runs runs each, then $runs alternating runs
# of `compare` at $spp (one thread, seeds 1..$runs) against the reference
# REF; the render's CPU time = the process's CPU time minus the median
# set-up. Prints the medians of each variant, and B's efficiency over A's;
# with $EFFICIENCY_LOG set, appends every run (scene, label, seed, CPU s,
# relMSE, relMSE r g b) and each median set-up to that file.
efficiency_pair() {
  name=$1 scene=$2 ref=$3
  shift 3
  for v in a b; do
    if [ $v = a ]; then vbin=$2 vsetup=$4; else vbin=$6 vsetup=$8; fi
    for r in $(seq "$runs"); do
      cpu "$vbin" render "$vsetup" -o "$dir/s.exr" --spp 1 --crop 0,0,1,1 --threads 1 \
        --quiet --no-png
    done | median >"$dir/setup-$v"
    if [ -n "${EFFICIENCY_LOG:-}" ]; then
      echo "$name setup $v $(cat "$dir/setup-$v")" >>"$EFFICIENCY_LOG"
    fi
  done
  rm -f "$dir"/runs-*
  for r in $(seq "$runs"); do
    for v in a b; do
      if [ $v = a ]; then vbin=$2 vmethod=$3; else vbin=$6 vmethod=$7; fi
      t=$(cpu "$vbin" compare "$scene" --methods "$vmethod" --spp "$spp" --reference "$ref" \
        --threads 1 --seed "$r" --quiet -o "$dir/c$v")
      e=$(awk -F, 'NR == 2 {print $5}' "$dir/c$v/results.csv")
      echo "$t $e" >>"$dir/runs-$v"
      if [ -n "${EFFICIENCY_LOG:-}" ]; then
        awk -F, -v n="$name" -v l="$v" -v r="$r" -v t="$t" \
          'NR == 2 {print n, l, r, t, $5, $6, $10, $14}' "$dir/c$v/results.csv" >>"$EFFICIENCY_LOG"
      fi
    done
  done
  for v in a b; do
    if [ $v = a ]; then label=$1; else label=$5; fi
    s=$(cat "$dir/setup-$v")
    awk -v s="$s" '{t = $1 - s; print t, $2, 1 / (t * $2)}' "$dir/runs-$v" >"$dir/eff-$v"
    t=$(awk '{print $1}' "$dir/eff-$v" | median)
    e=$(awk '{print $2}' "$dir/eff-$v" | median)
    f=$(awk '{print $3}' "$dir/eff-$v" | median)
    echo "$f" >"$dir/med-$v"
    ratio=$(awk -v x="$f" -v y="$(cat "$dir/med-a")" 'BEGIN {printf "%.2f", x / y}')
    printf '%-20s %-6s %10.3f %10.3f %12.4g %12.4g %8s\n' "$name" "$label" "$s" "$t" "$e" "$f" "$ratio"
  done
}
