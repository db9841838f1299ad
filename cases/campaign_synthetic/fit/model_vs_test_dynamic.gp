# Solver model vs every dynamic test (complex tangent at the preload): data in model_vs_test_dynamic.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'model_vs_test_dynamic.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Solver model vs every dynamic test (complex tangent at the preload)' noenhanced
set xlabel 'frequency [Hz]' noenhanced
set ylabel 'dynamic modulus |E*| [kPa]' noenhanced
plot \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'dynamic_preload25 test' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'dynamic_preload25 paper' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines lw 2 title 'dynamic_preload25 refit' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with points pt 7 ps 0.6 title 'dynamic_preload40 test' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines lw 2 title 'dynamic_preload40 paper' noenhanced, \
  'model_vs_test_dynamic.csv' skip 1 using 2:($1==5 ? $3 : 1/0) with lines lw 2 title 'dynamic_preload40 refit' noenhanced
