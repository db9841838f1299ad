# Fig. 12 style: dynamic modulus and phase angle of the SIT-BAR sweep, with and without the paper's
# Rayleigh damping, over the dynamic test (25 % preload) of the shipped synthetic campaign.
# Usage (from this folder, after `cushion run case.json -o out`): gnuplot -e "out='out'" plot.gp
if (!exists("out")) out = "out"
set datafile separator ","
set datafile commentschars "#"
set terminal pngcairo size 1200,480 font ",11"
set output out."/fig12_sweep.png"
set multiplot layout 1,2 title "SIT-BAR, 20 mm preload, base shaken 0.25 m/s^2 peak-to-peak"
set xlabel "frequency [Hz]"
set xrange [0:21]
set grid
set key right bottom
set ylabel "dynamic modulus [kPa]"
test = "../campaign_synthetic/campaign/dynamic_preload25.csv"
plot out."/sweep_rayleigh_sweep.csv" using "frequency_Hz":"dynamic_modulus_kPa" with linespoints pt 5 title "FE, Prony + Rayleigh (alpha 180 1/s, beta 1e-4 s)", \
     out."/sweep_no_rayleigh_sweep.csv" using "frequency_Hz":"dynamic_modulus_kPa" with linespoints pt 4 title "FE, Prony only", \
     test using "frequency_Hz":"dynamic_modulus_kPa" with points pt 7 title "dynamic test (campaign, 25 % preload)"
set ylabel "phase angle [deg]"
set key left top
plot out."/sweep_rayleigh_sweep.csv" using "frequency_Hz":"phase_deg" with linespoints pt 5 title "FE, Prony + Rayleigh", \
     out."/sweep_no_rayleigh_sweep.csv" using "frequency_Hz":"phase_deg" with linespoints pt 4 title "FE, Prony only", \
     test using "frequency_Hz":"phase_deg" with points pt 7 title "dynamic test"
unset multiplot
