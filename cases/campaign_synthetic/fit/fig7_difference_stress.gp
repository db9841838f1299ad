# Difference stress sigma(t1) - sigma(t2) of quasistatic_120mm_min: test vs hereditary model (paper Fig. 7): data in fig7_difference_stress.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,620 enhanced font 'sans,11'
} else {
  set terminal png size 1100,620
}
set output 'fig7_difference_stress.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 32
set xrange [21.33:30.17]
set xlabel 'loading time t1 [s]' noenhanced
set ylabel 'difference stress [kPa]' noenhanced
set title "Difference stress sigma(t1) - sigma(t2) of quasistatic_120mm_min:\ntest vs hereditary model (paper Fig. 7)" noenhanced
plot \
  'fig7_difference_stress.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title 'test' noenhanced, \
  'fig7_difference_stress.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#D55E00' title 'hereditary model (fit)' noenhanced
