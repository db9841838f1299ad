# Difference stress sigma(t1) - sigma(t2) of quasistatic_120mm_min (paper Fig. 7): data in fig7_difference_stress.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'fig7_difference_stress.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Difference stress sigma(t1) - sigma(t2) of quasistatic_120mm_min (paper Fig. 7)' noenhanced
set xlabel 'loading time t1 [s]' noenhanced
set ylabel 'difference stress [kPa]' noenhanced
plot \
  'fig7_difference_stress.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'test' noenhanced, \
  'fig7_difference_stress.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'hereditary model (fit)' noenhanced
