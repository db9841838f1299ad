# Decomposition of quasistatic_120mm_min: test = viscous + elastic part; hyperfoam fitted to the elastic part (paper Fig. 8): data in fig8_decomposition.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,620 enhanced font 'sans,11'
} else {
  set terminal png size 1100,620
}
set output 'fig8_decomposition.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 43
set xrange [-0.015:0.765]
set xlabel 'nominal strain [-]' noenhanced
set ylabel 'nominal stress [kPa]' noenhanced
set title "Decomposition of quasistatic_120mm_min:\ntest = viscous + elastic part; hyperfoam fitted to the elastic part (paper Fig. 8)" noenhanced
plot \
  'fig8_decomposition.csv' skip 1 every 5 using 2:($1==0 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title 'test sigma' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#D55E00' title 'viscous sigma_v (hereditary fit)' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#009E73' title 'elastic sigma_e = sigma - sigma_v' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#CC79A7' title 'hyperfoam fit (paper method)' noenhanced, \
  'fig8_decomposition.csv' skip 1 using 2:($1==4 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#E69F00' title 'hyperfoam after refit (long term)' noenhanced
