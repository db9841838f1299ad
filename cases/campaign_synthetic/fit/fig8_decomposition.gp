# Decomposition of quasistatic_120mm_min (paper Fig. 8): data in fig8_decomposition.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'fig8_decomposition.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Decomposition of quasistatic_120mm_min (paper Fig. 8)' noenhanced
set xlabel 'nominal strain [-]' noenhanced
set ylabel 'nominal stress [kPa]' noenhanced
plot \
  'fig8_decomposition.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'test sigma' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'viscous sigma_v (hereditary fit)' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines lw 2 title 'elastic sigma_e = sigma - sigma_v' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with lines lw 2 title 'hyperfoam fit (paper method)' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines lw 2 title 'hyperfoam after refit (long term)' noenhanced
