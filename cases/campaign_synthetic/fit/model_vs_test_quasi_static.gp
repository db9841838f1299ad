# Quasi-static tests (points) vs the solver's model: paper's material (dashed), refit (solid): data in model_vs_test_quasi_static.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,620 enhanced font 'sans,11'
} else {
  set terminal png size 1100,620
}
set output 'model_vs_test_quasi_static.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 49
set xrange [-0.015:0.765]
set xlabel 'nominal strain [-]' noenhanced
set ylabel 'nominal stress [kPa]' noenhanced
set title "Quasi-static tests (points) vs the solver's model:\npaper's material (dashed), refit (solid)" noenhanced
plot \
  'model_vs_test_quasi_static.csv' skip 1 every 7 using 2:($1==0 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title 'quasistatic_120mm_min: test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#0072B2' title 'quasistatic_120mm_min: paper''s material' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#0072B2' title 'quasistatic_120mm_min: refit' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 every 12 using 2:($1==3 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#D55E00' title 'quasistatic_30mm_min: test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#D55E00' title 'quasistatic_30mm_min: paper''s material' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==5 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#D55E00' title 'quasistatic_30mm_min: refit' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 every 8 using 2:($1==6 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#009E73' title 'quasistatic_480mm_min: test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==7 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#009E73' title 'quasistatic_480mm_min: paper''s material' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==8 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#009E73' title 'quasistatic_480mm_min: refit' noenhanced
