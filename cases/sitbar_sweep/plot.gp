# Fig. 12 style: dynamic modulus and phase angle of the SIT-BAR sweep, with and without the paper's
# Rayleigh damping, drawn over the dynamic test (25 % preload) of the shipped synthetic campaign.
# Usage (from this folder, after `cushion run case.json -o OUT`): gnuplot -e "out='OUT'" plot.gp
# (run.sh does both). The note under the plots says what is and is not compared.
reset
if (!exists("out")) out = "out"
set datafile separator ","
set datafile commentschars "#"
set terminal pngcairo size 1300,640 font ",11"
set output out."/fig12_sweep.png"
set multiplot layout 1,2 title "SIT-BAR on the 400 x 400 x 80 mm block (FE, 20 mm preload, base shaken 0.25 m/s^2 peak-to-peak)\nvs the campaign's dynamic test (80 mm cube, full-face platen, 25 % preload)" noenhanced
set bmargin 11
set label 1 "Not like for like. FE: (indenter force amplitude / contact area at the 20 mm base state) / (base amplitude / 80 mm), a structural value of the block\nunder the SIT-BAR: the compression under the indenter is not uniform (20 mm only under the lowest points of the lobes) and the foam around the\ncontact patch also carries load. Test: stress / strain of the cube compressed uniformly to 25 %. The foam model is the one fitted to this test\n(cases/campaign_synthetic/fit: on the cube it gives the test's |E*| within 0.6 % and its phase within 0.1 deg), so the gap is the structure and the definition, not the material.\nThe paper's Fig. 12 sets the same two quantities side by side." at screen 0.01, screen 0.13 left font ",10" noenhanced
set xlabel "frequency [Hz]"
set xrange [0.5:20.5]
set grid
set key right bottom noenhanced
set ylabel "dynamic modulus |E*| [kPa]"
test = "../campaign_synthetic/campaign/dynamic_preload25.csv"
plot out."/sweep_rayleigh_sweep.csv" using "frequency_Hz":"dynamic_modulus_kPa" with linespoints pt 5 title "FE, Prony + Rayleigh (alpha 180 1/s, beta 1e-4 s)", \
     out."/sweep_no_rayleigh_sweep.csv" using "frequency_Hz":"dynamic_modulus_kPa" with linespoints pt 4 title "FE, Prony only", \
     test using "frequency_Hz":"dynamic_modulus_kPa" with points pt 7 title "dynamic test (campaign, 25 % preload)"
unset label 1
set ylabel "phase angle [deg]"
set key left bottom
plot out."/sweep_rayleigh_sweep.csv" using "frequency_Hz":"phase_deg" with linespoints pt 5 title "FE, Prony + Rayleigh", \
     out."/sweep_no_rayleigh_sweep.csv" using "frequency_Hz":"phase_deg" with linespoints pt 4 title "FE, Prony only", \
     test using "frequency_Hz":"phase_deg" with points pt 7 title "dynamic test"
unset multiplot
