#!/bin/sh
# Runs the SIT-BAR sweep case and draws Fig. 12 (PNG) and its data (CSV) into OUT (default: out).
# Usage: cases/sitbar_sweep/run.sh [path/to/cushion] [OUT]
# Relative CUSHION and OUT are taken from the folder the script is called from (e.g. the repository root:
# `bash cases/sitbar_sweep/run.sh build/tools/cushion out_sweep`); default CUSHION: the repository's build/tools/cushion.
set -e
here=$(cd "$(dirname "$0")" && pwd)
absolute() { case "$1" in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$PWD/$1" ;; esac; }
CUSHION=$(absolute "${1:-$here/../../build/tools/cushion}")
OUT=$(absolute "${2:-out}")
"$CUSHION" run "$here/case.json" -o "$OUT" --overwrite  # re-running the script replaces OUT
# fig12.csv: FE (with / without Rayleigh) and test side by side, one row per frequency.
awk -F, 'FNR == 1 { file++ } /^#/ || /^frequency/ { next }
         file == 1 { E1[$1] = $18; P1[$1] = $21; f[$1] = 1 } file == 2 { E2[$1] = $18; P2[$1] = $21 }
         file == 3 { Et[$1] = $2; Pt[$1] = $3 }
         END { print "frequency_Hz,E_rayleigh_kPa,phase_rayleigh_deg,E_no_rayleigh_kPa,phase_no_rayleigh_deg,E_test_kPa,phase_test_deg";
               for (k = 1; k <= 20; k++) if (k in f) print k "," E1[k] "," P1[k] "," E2[k] "," P2[k] "," Et[k] "," Pt[k] }' \
    "$OUT/sweep_rayleigh_sweep.csv" "$OUT/sweep_no_rayleigh_sweep.csv" \
    "$here/../campaign_synthetic/campaign/dynamic_preload25.csv" > "$OUT/fig12.csv"
if command -v gnuplot > /dev/null; then
  (cd "$here" && gnuplot -e "out='$OUT'" plot.gp)
  echo "wrote $OUT/fig12_sweep.png and $OUT/fig12.csv"
else
  echo "run.sh: gnuplot not found; wrote $OUT/fig12.csv (draw with: cd $here && gnuplot -e \"out='$OUT'\" plot.gp)" >&2
fi
