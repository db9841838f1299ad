# Solver model vs every quasi-static test: data in model_vs_test_quasi_static.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'model_vs_test_quasi_static.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Solver model vs every quasi-static test' noenhanced
set xlabel 'nominal strain [-]' noenhanced
set ylabel 'nominal stress [kPa]' noenhanced
plot \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'quasistatic_120mm_min test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'quasistatic_120mm_min paper' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines lw 2 title 'quasistatic_120mm_min refit' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with points pt 7 ps 0.6 title 'quasistatic_30mm_min test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines lw 2 title 'quasistatic_30mm_min paper' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==5 ? $3 : 1/0) with lines lw 2 title 'quasistatic_30mm_min refit' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==6 ? $3 : 1/0) with points pt 7 ps 0.6 title 'quasistatic_480mm_min test' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==7 ? $3 : 1/0) with lines lw 2 title 'quasistatic_480mm_min paper' noenhanced, \
  'model_vs_test_quasi_static.csv' skip 1 using 2:($1==8 ? $3 : 1/0) with lines lw 2 title 'quasistatic_480mm_min refit' noenhanced
