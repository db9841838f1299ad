#!/usr/bin/env bash
# Material-point demo of the paper's foam (cases/materials/paper_table3.json). Run from the repo root
# after building in ./build. Writes CSV tables and PNG plots into ./results/point/.
#   1. The 80 mm cube test: nominal strain to -0.75 at 120 mm/min (60 mm in 30 s), 2 s hold, unload
#      at the same rate (platen control: the machine cannot pull the lagging foam).
#   2. A 1 Hz sine of 1 % nominal strain about a 25 % compressive preload held 60 s.
set -euo pipefail
cd "$(dirname "$0")/.."
cushion=./build/tools/cushion
material=cases/materials/paper_table3.json
out=results/point
[ -x "$cushion" ] || { echo "demo: $cushion not found; build first (cmake -S . -B build && cmake --build build)" >&2; exit 1; }
mkdir -p "$out"

"$cushion" point -m "$material" --mode uniaxial_free --platen \
  --ramp=-0.75,30,600 --hold 2,20 --ramp 0,30,600 --hold 30,60 -o "$out/cube.csv"
"$cushion" point -m "$material" --mode uniaxial_free \
  --ramp=-0.25,10,100 --hold 60,60 --sine 0.01,1,10,200 -o "$out/sine_1Hz.csv"

if command -v gnuplot >/dev/null 2>&1; then
  terminal=png
  gnuplot -e "set terminal pngcairo" >/dev/null 2>&1 && terminal="pngcairo"
  # Columns: 2 control (nominal strain), 1 time_s, 8 P11_kPa; plotted compression-positive.
  gnuplot <<GNUPLOT
set terminal $terminal size 900,650
set datafile separator ","
set key top left
set grid
set output "$out/cube_stress_strain.png"
set title "Cube test (uniaxial, 120 mm/min on 80 mm, platen control): paper Table 3 Prony + assumed hyperfoam"
set xlabel "compression, nominal strain [%]"
set ylabel "nominal stress [kPa] (compression positive)"
plot "$out/cube.csv" every ::1 using (-100*\$2):(-\$8) with lines lw 2 title "load - hold - unload"
set output "$out/sine_1Hz_stress_strain.png"
set title "1 Hz, 1 % sine about a 25 % preload held 60 s"
plot "$out/sine_1Hz.csv" every ::1 using (-100*\$2):(\$1 > 70 ? -\$8 : 1/0) with lines lw 2 title "steady cycles", \
     "$out/sine_1Hz.csv" every ::1 using (-100*\$2):(\$1 <= 70 ? -\$8 : 1/0) with lines dt 2 title "preload and hold"
GNUPLOT
  plots="$out/cube_stress_strain.png $out/sine_1Hz_stress_strain.png"
else
  plots="(none: gnuplot not installed; install gnuplot-nox)"
fi

echo "demo: material-point outputs in $out/"
echo "  tables: $out/cube.csv $out/sine_1Hz.csv"
echo "  plots:  $plots"

# 3. Calibration: the paper's method plus the consistency refit on the shipped SYNTHETIC campaign.
echo; echo "== cushion fit: shipped synthetic campaign -> material =="
"$cushion" fit cases/campaign_synthetic/campaign/campaign.json -o results/fit --overwrite

# 4. The FE cube test with the paper's foam (hyperfoam + Table 3 Prony), frames for ParaView.
echo; echo "== cushion run: the paper's 80 mm cube (load, hold, unload) =="
"$cushion" run cases/cube_compression/case.json -o results/cube --quiet --overwrite

# 5. Compare, diagnose, extend on a campaign with a hidden effect (cases/hidden_effects/README.md).
echo; echo "== compare -> diagnose -> add the effect -> compare again =="
campaign=cases/hidden_effects/campaign_friction/campaign.json
rm -rf results/loop
"$cushion" compare cases/hidden_effects/base_material.json "$campaign" -o results/loop/compare_baseline \
  --label baseline --history results/loop/history
"$cushion" diagnose cases/hidden_effects/base_material.json "$campaign" -o results/loop/diagnose
"$cushion" compare results/loop/diagnose/material_extended.json "$campaign" -o results/loop/compare_extended \
  --label extended --history results/loop/history

# 6. The paper's validation (section 4): SIT-BAR pressed 60 mm in and out (Figs. 9-11), then the
#    1-20 Hz sweep about a 20 mm preload with and without Rayleigh damping (Fig. 12).
echo; echo "== cushion run: SIT-BAR 60 mm into the 400 x 400 x 80 mm block and back (about 35 s) =="
rm -rf results/sitbar results/sweep
"$cushion" run cases/sitbar_quasistatic/case.json -o results/sitbar --quiet
bash cases/sitbar_quasistatic/plot.sh "$PWD/results/sitbar" "$PWD/$cushion"
echo; echo "== cushion run: SIT-BAR 20 mm preload, 1-20 Hz steady-state sweep (under 1 min) =="
sh cases/sitbar_sweep/run.sh "$PWD/$cushion" "$PWD/results/sweep" > results/sweep.log || { cat results/sweep.log; exit 1; }
tail -n 1 results/sweep.log

echo
echo "demo: all outputs in results/"
echo "  results/point/             material-point tables and plots"
echo "  results/fit/               fitted material (material.json), ABAQUS cards, report.md, plots"
echo "  results/cube/results.pvd   open in ParaView (File > Open, Apply, Warp By Vector)"
echo "  results/loop/              compare (baseline), diagnosis.md, compare (extended), history/history_plot.png"
echo "  results/sitbar/            SIT-BAR run: results.pvd (ParaView), contact_sitbar.csv, fig11.png, force_indentation.png"
echo "  results/sweep/             SIT-BAR sweep: fig12_sweep.png, fig12.csv, sweep_*_sweep.csv, sweep_rayleigh_sweep.pvd"
