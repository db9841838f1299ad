# Dynamic tests (points) vs the solver's model at each preload: paper's material (dashed), refit (solid): data in model_vs_test_dynamic.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,860 enhanced font 'sans,11'
} else {
  set terminal png size 1100,860
}
set output 'model_vs_test_dynamic.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 51
set xrange [0.62:20.38]
set xlabel 'frequency [Hz]' noenhanced
set ylabel 'dynamic modulus |E*| [kPa]' noenhanced
set multiplot layout 2,1 title "Dynamic tests (points) vs the solver's model at each preload:\npaper's material (dashed), refit (solid)" noenhanced
plot \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title 'dynamic_preload25: test |E*|' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#0072B2' title 'dynamic_preload25: paper''s material |E*|' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#0072B2' title 'dynamic_preload25: refit |E*|' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==6 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#D55E00' title 'dynamic_preload40: test |E*|' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==8 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#D55E00' title 'dynamic_preload40: paper''s material |E*|' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==10 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#D55E00' title 'dynamic_preload40: refit |E*|' noenhanced
set ylabel 'phase [deg]' noenhanced
unset label
plot \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title 'dynamic_preload25: test phase' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#0072B2' title 'dynamic_preload25: paper''s material phase' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==5 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#0072B2' title 'dynamic_preload25: refit phase' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==7 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#D55E00' title 'dynamic_preload40: test phase' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==9 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#D55E00' title 'dynamic_preload40: paper''s material phase' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==11 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#D55E00' title 'dynamic_preload40: refit phase' noenhanced
unset multiplot
