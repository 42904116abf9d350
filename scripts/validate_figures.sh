#!/usr/bin/env bash
# make validate, the papers' figures, called by validate.sh:
#   1. Frederickx2017 Fig. 1: the backlit cube (scenes/fig1_cube.json) at seven
#      densities from optically thin to thick, every dipole against volpath;
#   2. Frederickx2017 Fig. 6: the dragon's medium on procedural shapes
#      (scenes/fig6_forward.json);
#   3. Jensen2001: the dipole's speed-up over volpath at
#      equal error on a dense marble sphere (scenes/marble_sphere_sky.json).
# Usage: validate_figures.sh BUILD_DIR OUT_DIR [PART...]   (PART: fig1 fig6 jensen)
#
# Everything is written under OUT_DIR/figures/ (never into docs/):
#   figures.md                     the tables of docs/results.md ("The papers' figures")
#   fig1/d<DENSITY>/{main,single,iso}/   `subsurf compare` folders (results.json,
#                                  images, error maps); fig6/ and jensen/ alike
#   plots/fig1_mean_ratio.svg, plots/fig1_images.svg, plots/fig6_images.svg,
#   plots/jensen_convergence.svg   the figures of docs/plots/ (SVG; the image
#                                  grids embed the compare PNGs)
#
# Budgets (samples per pixel, so that the numbers are the same on any machine
# apart from the times): Fig. 1 at 64 x 64 pixels, methods 32 spp, reference
# (volpath) 1024 spp; Fig. 6 at 120 x 84, methods 32 spp, reference 512 spp;
# Jensen at 32 x 32, methods 64 spp, reference 1024 spp. About 10 minutes of
# CPU time (Fig. 1: 310 s measured; Fig. 6 and Jensen estimated at 2 and 3
# minutes); compare's times and the speed-ups are wall-clock and depend on
# the machine's load.
#
# Methods: compare's, plus two that compare cannot name and that are rendered
# against the same reference (--reference): "dipole+single" (the dipole with
# the material's "single_scattering": true) and "iso-ref" (volpath in the
# similar isotropic medium sigma_s' = (1 - g) sigma_s: the ground truth of a
# diffusion model, the 'iso. ref.' row of Frederickx2017's Fig. 1).
set -euo pipefail
build=${1:-build}
out=${2:-out/validate}/figures
shift $(($# < 2 ? $# : 2))
parts=${*:-fig1 fig6 jensen}
subsurf=$build/subsurf

if [ ! -x "$subsurf" ]; then
  echo "validate_figures.sh: $subsurf not found; run 'make build' first" >&2
  exit 2
fi
if ! command -v jq >/dev/null; then
  echo "validate_figures.sh: jq not found (scripts/install-deps.sh installs it)" >&2
  exit 2
fi
mkdir -p "$out/plots"
start=$SECONDS
md=$out/figures.md
: >"$md"

# variant SRC DST JQ_FILTER: a copy of a scene with some keys changed.
variant() { jq "$3" "$1" >"$2"; }

# compare_run DIR SCENE ARGS...: one `subsurf compare`, its log kept in DIR.log.
compare_run() {
  local dir=$1 scene=$2
  shift 2
  mkdir -p "$dir"
  echo "   compare $scene $* -o $dir"
  "$subsurf" compare "$scene" -o "$dir" --quiet "$@" >"$dir.log" 2>&1 || {
    cat "$dir.log" >&2
    echo "validate_figures.sh: compare failed (log: $dir.log)" >&2
    exit 1
  }
}

# rows LABEL_PREFIX DIR [RENAME]: one TSV line per method of DIR/results.json:
# name, mean ratio r g b, relMSE, converged relMSE, seconds, spp.
rows() {
  jq -r --arg rename "${2:-}" '.methods[] |
    [(if $rename != "" then $rename else .method end),
     .mean_ratio_rgb[0], .mean_ratio_rgb[1], .mean_ratio_rgb[2], .rel_mse,
     (.converged_rel_mse // "nan"), .seconds, .spp] | @tsv' "$1/results.json"
}

# One scene, three compare runs against one reference: the methods
# (with volpath), the dipole with single scattering, and the isotropic
# similar medium. Prints the TSV rows of all three.
# scene_set DIR SCENE METHODS SPP REF_SPP
scene_set() {
  local dir=$1 scene=$2 methods=$3 spp=$4 ref_spp=$5
  variant "$scene" "$dir/single.json" \
    '.materials |= map(if .type == "translucent" then .single_scattering = true else . end)'
  variant "$scene" "$dir/iso.json" \
    '.media |= map(.sigma_s = [.sigma_s[] * (1 - (.phase.g // 0))] | .phase = "iso")'
  compare_run "$dir/main" "$scene" --methods "$methods" --spp "$spp" --reference-spp "$ref_spp"
  compare_run "$dir/single" "$dir/single.json" --methods dipole --spp "$spp" \
    --reference "$dir/main/reference.exr"
  compare_run "$dir/iso" "$dir/iso.json" --methods volpath --spp "$spp" \
    --reference "$dir/main/reference.exr"
  # The light that never scatters (the boundary's reflection, and what is
  # seen through the object): volpath with every scattering event turned into
  # absorption, in the medium and in the isotropic one.
  local absorbing='.media |= map(.sigma_a = [range(0; 3) as $i | .sigma_a[$i] + .sigma_s[$i]] | .sigma_s = [0, 0, 0])'
  variant "$scene" "$dir/unscattered.json" "$absorbing"
  variant "$dir/iso.json" "$dir/iso-unscattered.json" "$absorbing"
  compare_run "$dir/unscattered" "$dir/unscattered.json" --methods volpath --spp "$spp" \
    --reference "$dir/main/reference.exr"
  compare_run "$dir/iso-unscattered" "$dir/iso-unscattered.json" --methods volpath --spp "$spp" \
    --reference "$dir/main/reference.exr"
  {
    rows "$dir/main"
    rows "$dir/single" dipole+single
    rows "$dir/iso" iso-ref
    rows "$dir/unscattered" unscattered
    rows "$dir/iso-unscattered" iso-unscattered
  } >"$dir/rows.tsv"
}

# ratio_table TSV SEES_UNSCATTERED: the markdown table of scene sets (TSV:
# key, then rows' columns). Besides the total, the ratio of the scattered light
# alone to the reference's: ss = (ratio - U_own) / (1 - U), U the unscattered
# light's share of the reference and U_own that of the method's own medium
# (iso-ref's differs); with SEES_UNSCATTERED = 0 the BSSRDF methods render no
# unscattered light at all (index-matched boundary: the bssrdf integrator
# never looks through the object), so for them U_own = 0.
ratio_table() {
  echo "| key | method | R | G | B | ss R | ss G | ss B | relMSE | relMSE floor | s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F'\t' -v sees="$2" '
    NR == FNR { if ($2 == "unscattered" || $2 == "iso-unscattered") for (c = 0; c < 3; c++) U[$1, $2, c] = $(3 + c); next }
    $2 != "unscattered" && $2 != "iso-unscattered" {
      line = sprintf("| %s | %s | %.3f | %.3f | %.3f |", $1, $2, $3, $4, $5)
      u = ($2 == "iso-ref") ? "iso-unscattered" : "unscattered"
      volumetric = ($2 == "volpath" || $2 == "iso-ref")
      for (c = 0; c < 3; c++) {
        own = (volumetric || sees) ? U[$1, u, c] : 0
        line = line sprintf(" %.3f |", ($(3 + c) - own) / (1 - U[$1, "unscattered", c]))
      }
      printf "%s %.3g | %.3g | %.2f |\n", line, $6, $7, $8
    }' "$1" "$1"
}

# table TSV: the markdown table of one scene set (ratios, relMSE, time).
table() {
  echo "| method | R | G | B | relMSE | relMSE floor | s |"
  echo "|---|---|---|---|---|---|---|"
  awk -F'\t' '{ printf "| %s | %.3f | %.3f | %.3f | %.3g | %.3g | %.2f |\n", $1, $2, $3, $4, $5, $6, $7 }' "$1"
}

# svg_grid OUT ROW_LABELS COLUMN_LABELS CELL_PX FILE...: an SVG with the PNGs
# (row-major) embedded, so that it shows on its own.
svg_grid() {
  local file=$1 rows=$2 cols=$3 px=$4
  shift 4
  local nr nc
  nr=$(wc -w <<<"$rows")
  nc=$(wc -w <<<"$cols")
  local w=$((90 + nc * (px + 4))) h=$((20 + nr * (px + 4)))
  {
    echo "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"$w\" height=\"$h\" font-family=\"sans-serif\" font-size=\"11\">"
    echo "<rect width=\"$w\" height=\"$h\" fill=\"white\"/>"
    local c=0
    for label in $cols; do
      echo "<text x=\"$((90 + c * (px + 4) + px / 2))\" y=\"14\" text-anchor=\"middle\">$label</text>"
      c=$((c + 1))
    done
    local r=0
    for label in $rows; do
      echo "<text x=\"84\" y=\"$((20 + r * (px + 4) + px / 2))\" text-anchor=\"end\">$label</text>"
      r=$((r + 1))
    done
    local i=0
    for png in "$@"; do
      r=$((i / nc))
      c=$((i % nc))
      echo "<image x=\"$((90 + c * (px + 4)))\" y=\"$((20 + r * (px + 4)))\" width=\"$px\" height=\"$px\" href=\"data:image/png;base64,$(base64 -w0 "$png")\"/>"
      i=$((i + 1))
    done
    echo "</svg>"
  } >"$file"
}

# svg_lines OUT TITLE XLABEL YLABEL YMIN YMAX < TSV(series x y): a log-x line
# chart with one line per series, a grey band at y = 0.9..1.1 when the range
# holds 1 (ratio charts).
svg_lines() {
  awk -F'\t' -v title="$2" -v xl="$3" -v yl="$4" -v ymin="$5" -v ymax="$6" '
    { s = $1; if (!(s in seen)) { seen[s] = 1; order[++ns] = s }
      n[s]++; X[s, n[s]] = log($2) / log(10); Y[s, n[s]] = $3
      if (xmin == "" || X[s, n[s]] < xmin) xmin = X[s, n[s]]
      if (xmax == "" || X[s, n[s]] > xmax) xmax = X[s, n[s]] }
    function px(x) { return 60 + (x - xmin) / (xmax - xmin + 1e-12) * 440 }
    function py(y) { y = y < ymin ? ymin : (y > ymax ? ymax : y); return 290 - (y - ymin) / (ymax - ymin) * 250 }
    END {
      split("#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #8c564b #e377c2 #17becf", col, " ")
      printf "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"330\" font-family=\"sans-serif\" font-size=\"11\">\n"
      printf "<rect width=\"640\" height=\"330\" fill=\"white\"/>\n"
      printf "<text x=\"280\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">%s</text>\n", title
      if (ymin < 1 && ymax > 1)
        printf "<rect x=\"60\" y=\"%.1f\" width=\"440\" height=\"%.1f\" fill=\"#eee\"/>\n", py(1.1), py(0.9) - py(1.1)
      printf "<rect x=\"60\" y=\"40\" width=\"440\" height=\"250\" fill=\"none\" stroke=\"black\"/>\n"
      for (e = int(xmin); e <= xmax + 1e-9; e++) {
        printf "<line x1=\"%.1f\" y1=\"290\" x2=\"%.1f\" y2=\"295\" stroke=\"black\"/>", px(e), px(e)
        printf "<text x=\"%.1f\" y=\"307\" text-anchor=\"middle\">%g</text>\n", px(e), 10 ^ e
      }
      for (k = 0; k <= 4; k++) {
        y = ymin + k * (ymax - ymin) / 4
        printf "<line x1=\"55\" y1=\"%.1f\" x2=\"60\" y2=\"%.1f\" stroke=\"black\"/>", py(y), py(y)
        printf "<text x=\"52\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", py(y) + 4, y
      }
      printf "<text x=\"280\" y=\"324\" text-anchor=\"middle\">%s</text>\n", xl
      printf "<text x=\"14\" y=\"165\" text-anchor=\"middle\" transform=\"rotate(-90 14 165)\">%s</text>\n", yl
      for (i = 1; i <= ns; i++) {
        s = order[i]; pts = ""
        for (j = 1; j <= n[s]; j++) pts = pts sprintf("%.1f,%.1f ", px(X[s, j]), py(Y[s, j]))
        printf "<polyline points=\"%s\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\"/>\n", pts, col[(i - 1) % 8 + 1]
        printf "<text x=\"510\" y=\"%d\" fill=\"%s\">%s</text>\n", 50 + 15 * i, col[(i - 1) % 8 + 1], s
      }
      printf "</svg>\n"
    }' >"$1"
}

for part in $parts; do
  case $part in
  fig1)
    # Frederickx2017 Fig. 1. media[0].scale is the density; the cube is 1 unit, so
    # its optical thickness in transport mean free paths is
    # n = scale * sigma_t' = scale * ((1 - g) sigma_s + sigma_a) =
    # 0.12 .. 0.18 x scale (red .. blue).
    densities="1 3 10 30 100 300 1000"
    echo "== Frederickx2017 Fig. 1: the backlit cube at densities $densities"
    mkdir -p "$out/fig1"
    : >"$out/fig1/rows.tsv"
    for d in $densities; do
      dir=$out/fig1/d$d
      mkdir -p "$dir"
      variant scenes/fig1_cube.json "$dir/scene.json" \
        ".media[0].scale = $d | .camera.resolution = [64, 64]"
      scene_set "$dir" "$dir/scene.json" volpath,dipole,dirpole,fwddip,fwddip-brdf,single 32 1024
      awk -v d="$d" -F'\t' '{ print d "\t" $0 }' "$dir/rows.tsv" >>"$out/fig1/rows.tsv"
    done
    ratio_table "$out/fig1/rows.tsv" 0 >"$out/fig1/table.md"
    {
      echo "### Fig. 1: backlit cube, mean radiance over the cube relative to volpath"
      echo
      echo "Ratio of each method's mean to the 1024-spp volpath reference's (R, G, B) and of the scattered light alone (ss); relMSE at 32 spp."
      echo
      sed 's/| key |/| density |/' "$out/fig1/table.md"
      echo
    } >>"$md"
    # The red channel (the most translucent), total and scattered light alone.
    for col in total:4 ss:7; do
      awk -F'|' -v c="${col#*:}" 'NR > 2 { gsub(/ /, ""); if ($3 !~ /^(volpath|single)$/) print $3 "\t" $2 "\t" $c }' \
        "$out/fig1/table.md" | svg_lines "$out/plots/fig1_ratio_${col%%:*}.svg" \
        "Fig. 1 cube, red: mean radiance / volpath's (${col%%:*})" "density (media[0].scale)" "ratio" 0 2
    done
    pngs=()
    for d in 1 10 100 1000; do
      pngs+=("$out/fig1/d$d/main/reference.png" "$out/fig1/d$d/iso/volpath.png"
        "$out/fig1/d$d/main/dipole.png" "$out/fig1/d$d/single/dipole.png"
        "$out/fig1/d$d/main/dirpole.png" "$out/fig1/d$d/main/fwddip.png")
    done
    svg_grid "$out/plots/fig1_images.svg" "scale_1 scale_10 scale_100 scale_1000" \
      "volpath_ref iso-ref dipole dipole+single dirpole fwddip" 64 "${pngs[@]}"
    ;;
  fig6)
    echo "== Frederickx2017 Fig. 6: the dragon's medium on procedural shapes"
    dir=$out/fig6
    mkdir -p "$dir"
    variant scenes/fig6_forward.json "$dir/scene.json" '.camera.resolution = [120, 84]'
    scene_set "$dir" "$dir/scene.json" volpath,dipole,dirpole,fwddip,pbd 32 512
    {
      echo "### Fig. 6: the dragon's medium (scenes/fig6_forward.json)"
      echo
      awk '{ print "-\t" $0 }' "$dir/rows.tsv" >"$dir/keyed.tsv"
      ratio_table "$dir/keyed.tsv" 1 | sed 's/| key |/| |/'
      echo
    } >>"$md"
    svg_grid "$out/plots/fig6_images.svg" "image error" \
      "volpath_ref dipole+single dirpole fwddip pbd" 112 \
      "$dir/main/reference.png" "$dir/single/dipole.png" "$dir/main/dirpole.png" \
      "$dir/main/fwddip.png" "$dir/main/pbd.png" \
      "$dir/main/volpath-error.png" "$dir/single/dipole-error.png" \
      "$dir/main/dirpole-error.png" "$dir/main/fwddip-error.png" "$dir/main/pbd-error.png"
    ;;
  jensen)
    echo "== Jensen2001: dipole against volpath at equal error"
    dir=$out/jensen
    mkdir -p "$dir"
    variant scenes/marble_sphere_sky.json "$dir/scene.json" '.camera.resolution = [32, 32]'
    variant "$dir/scene.json" "$dir/single.json" \
      '.materials |= map(if .type == "translucent" then .single_scattering = true else . end)'
    # Side by side in one run: volpath and the dipole in one compare, the
    # dipole with single scattering right after against the same reference.
    compare_run "$dir/main" "$dir/scene.json" --methods volpath,dipole,pbd --spp 64 \
      --reference-spp 1024
    compare_run "$dir/single" "$dir/single.json" --methods dipole --spp 64 \
      --reference "$dir/main/reference.exr"
    # The passes of every method: name, spp, seconds, relMSE.
    {
      jq -r '.methods[] | .method as $m | .passes[] | [$m, .spp, .seconds, .rel_mse] | @tsv' \
        "$dir/main/results.json"
      jq -r '.methods[] | .passes[] | ["dipole+single", .spp, .seconds, .rel_mse] | @tsv' \
        "$dir/single/results.json"
    } >"$dir/passes.tsv"
    awk -F'\t' '{ print $1 "\t" $3 "\t" $4 }' "$dir/passes.tsv" | awk -F'\t' '{ $3 = log($3) / log(10); print $1 "\t" $2 "\t" $3 }' OFS='\t' |
      svg_lines "$out/plots/jensen_convergence.svg" \
        "Marble sphere (n = 88): relMSE against volpath's reference over time" \
        "wall seconds" "log10 relMSE" -3 1
    # Fit relMSE = c + k / t per method (least squares weighted by 1/relMSE^2,
    # all passes from 4 spp on), then the time each method needs to reach a
    # target error E: t(E) = k / (E - c), infinite at or below its floor c.
    # c includes the reference's own noise, the same for every method, so it
    # is also volpath's c; a model's bias is c - c(volpath). A floor the
    # passes cannot resolve yet (variance still far above it) is bounded below
    # by the squared relative bias of the mean, b^2 = mean over channels of
    # (ratio - 1)^2, so c = max(c_fit, c(volpath) + b^2).
    {
      rows "$dir/main"
      rows "$dir/single" dipole+single
    } >"$dir/rows.tsv"
    awk -F'\t' 'NR == FNR { b2[$1] = ((($2 - 1) ^ 2) + (($3 - 1) ^ 2) + (($4 - 1) ^ 2)) / 3; next }
      $2 >= 4 {
        m = $1; if (!(m in n)) order[++nm] = m
        x = 1 / $3; y = $4; w = 1 / (y * y)
        n[m]++; W[m] += w; Sx[m] += w * x; Sy[m] += w * y; Sxx[m] += w * x * x; Sxy[m] += w * x * y
        last[m] = y; lastt[m] = $3 }
      END {
        for (i = 1; i <= nm; i++) {
          m = order[i]; d = W[m] * Sxx[m] - Sx[m] * Sx[m]
          k[m] = (W[m] * Sxy[m] - Sx[m] * Sy[m]) / d; c[m] = (Sy[m] - k[m] * Sx[m]) / W[m]
          if (c[m] < 0) c[m] = 0
        }
        for (i = 1; i <= nm; i++) if (order[i] != "volpath" && c[order[i]] < c["volpath"] + b2[order[i]]) c[order[i]] = c["volpath"] + b2[order[i]]
        E = last["volpath"]
        printf "Fits relMSE = c + k / t (t in wall seconds, passes from 4 spp; c at least c(volpath) + the squared bias of the mean):\n\n"
        printf "| method | k | c (floor) | bias c - c(volpath) | relMSE at 64 spp | s at 64 spp | s to volpath'"'"'s %.3g | speed-up |\n", E
        printf "|---|---|---|---|---|---|---|---|\n"
        for (i = 1; i <= nm; i++) {
          m = order[i]; t = (E > c[m]) ? k[m] / (E - c[m]) : -1
          tv = lastt["volpath"]
          printf "| %s | %.3g | %.3g | %.3g | %.3g | %.3g | %s | %s |\n", m, k[m], c[m], c[m] - c["volpath"], last[m], lastt[m],
            (t > 0 ? sprintf("%.3g", t) : "never"), (t > 0 ? sprintf("%.1f", tv / t) : "-")
        }
        printf "\nSpeed-up over volpath t_volpath(E) / t_method(E) at target relMSE E:\n\n| E |"
        for (i = 1; i <= nm; i++) if (order[i] != "volpath") printf " %s |", order[i]
        printf "\n|---|"
        for (i = 2; i <= nm; i++) printf "---|"
        printf "\n"
        split("1 0.3 0.1 0.05 0.03 0.02 0.01", targets, " ")
        for (j = 1; j <= 7; j++) {
          e = targets[j] + c["volpath"]; printf "| %.3g |", e
          tvol = k["volpath"] / (e - c["volpath"])
          for (i = 1; i <= nm; i++) {
            m = order[i]; if (m == "volpath") continue
            printf " %s |", (e > c[m]) ? sprintf("%.2g", tvol / (k[m] / (e - c[m]))) : "never"
          }
          printf "\n"
        }
      }' "$dir/rows.tsv" "$dir/passes.tsv" >"$dir/speedup.md"
    {
      echo "### Jensen et al. 2001: marble sphere, speed at equal error"
      echo
      table "$dir/rows.tsv"
      echo
      cat "$dir/speedup.md"
      echo
      echo "compare's own time_to_volpath_error (log-log line through all passes):"
      echo
      jq -r '.methods[] | "- \(.method): \(.time_to_volpath_error) s"' "$dir/main/results.json"
      echo
    } >>"$md"
    ;;
  *)
    echo "validate_figures.sh: unknown part '$part' (fig1, fig6, jensen)" >&2
    exit 2
    ;;
  esac
done
cat "$md"
echo "validate_figures.sh: done in $((SECONDS - start)) s; tables in $md, figures in $out/plots/"
