#!/usr/bin/env bash
# Fig. 11 style comparison and the force-indentation hysteresis of a finished SIT-BAR run.
# Usage (from anywhere): cases/sitbar_quasistatic/plot.sh OUT [CUSHION_BINARY]
#   OUT: the output folder of `cushion run cases/sitbar_quasistatic/case.json -o OUT`.
# Runs cube_same_rate.json (the 80 mm cube at the same 30 mm/min, same material) into OUT/cube if
# OUT/cube/history.csv is missing, then writes from the runs' CSVs:
#   OUT/fig11_sitbar.csv  time_s, indentation_mm, compression_pct, force_N, mean_pressure_kPa
#   OUT/fig11_cube.csv    time_s, displacement_mm, compression_pct, nominal_stress_kPa (tension of the
#                         bonded displacement-controlled platen on release clipped to 0: a real platen lifts off)
#   OUT/fig11.png         SIT-BAR mean contact pressure and cube nominal stress vs compression (% of 80 mm)
#   OUT/force_indentation.png  SIT-BAR force vs indentation, loading and unloading (hysteresis)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:?usage: plot.sh OUT [CUSHION_BINARY]}"
cushion="${2:-$here/../../build/tools/cushion}"
[ -f "$out/contact_sitbar.csv" ] || { echo "plot.sh: $out/contact_sitbar.csv not found (run the case first)" >&2; exit 1; }
if [ ! -f "$out/cube/history.csv" ]; then "$cushion" run "$here/cube_same_rate.json" -o "$out/cube" --overwrite > /dev/null; fi
awk -F, 'BEGIN { print "time_s,indentation_mm,compression_pct,force_N,mean_pressure_kPa" }
  /^#/ || $1 == "time_s" { next }
  { d = -$4; printf "%s,%.6g,%.6g,%.6g,%.6g\n", $1, d, 100 * d / 80, -$7, $10 }' "$out/contact_sitbar.csv" > "$out/fig11_sitbar.csv"
awk -F, 'BEGIN { print "time_s,displacement_mm,compression_pct,nominal_stress_kPa" }
  /^#/ { next }
  $1 == "time_s" { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  { d = -$col["top.U3_mm"]; s = -1e3 * $col["top.RF3_N"] / 1600; if (s < 0) s = 0
    printf "%s,%.6g,%.6g,%.6g\n", $1, d, 100 * d / 80, s }' \
  "$out/cube/history.csv" > "$out/fig11_cube.csv"
command -v gnuplot > /dev/null || { echo "plot.sh: gnuplot not found; CSVs written to $out" >&2; exit 0; }
gnuplot <<GP
set datafile separator ","
set terminal pngcairo size 800,560
set key left top
set grid
set output "$out/fig11.png"
set title "SIT-BAR mean contact pressure vs cube nominal stress (30 mm/min, same foam)"
set xlabel "compression: indentation / 80 mm [%]"
set ylabel "stress [kPa]"
plot "$out/fig11_sitbar.csv" using 3:5 skip 1 with linespoints pt 7 ps 0.5 title "SIT-BAR mean contact pressure", \
     "$out/fig11_cube.csv" using 3:4 skip 1 with lines lw 2 title "cube nominal stress"
set output "$out/force_indentation.png"
set title "SIT-BAR force vs indentation (press 120 s, release 120 s)"
set xlabel "indentation [mm]"
set ylabel "indenter force [N]"
plot "$out/fig11_sitbar.csv" using 2:4 skip 1 with linespoints pt 7 ps 0.5 title "FE, full-model force"
GP
echo "wrote $out/fig11.png, $out/force_indentation.png, $out/fig11_sitbar.csv, $out/fig11_cube.csv"
