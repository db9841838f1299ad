# Fig. 12 style: dynamic modulus and phase of the sweep vs the shipped campaign's dynamic test
# (25 % preload). Run from this folder after `cushion run case.json -o out`.
set datafile separator ","
set terminal pngcairo size 1100,450
set output "out/fig12_sweep.png"
set multiplot layout 1,2
set xlabel "frequency [Hz]"
set key left top
set ylabel "dynamic modulus [kPa]"
plot "out/sweep_rayleigh_sweep.csv" using 1:18 with linespoints title "FE, Rayleigh alpha=180, beta=1e-4", \
     "out/sweep_undamped_sweep.csv" using 1:18 with linespoints title "FE, no Rayleigh damping", \
     "../campaign_synthetic/campaign/dynamic_preload25.csv" using 1:2 with points pt 7 title "dynamic test, 25 % preload"
set ylabel "phase angle [deg]"
plot "out/sweep_rayleigh_sweep.csv" using 1:21 with linespoints title "FE, Rayleigh", \
     "out/sweep_undamped_sweep.csv" using 1:21 with linespoints title "FE, no Rayleigh", \
     "../campaign_synthetic/campaign/dynamic_preload25.csv" using 1:3 with points pt 7 title "dynamic test"
unset multiplot
