# |E*| (left axis) and phase (right axis) of dynamic_preload25: test vs Prony fit (paper Fig. 4): data in fig4_dynamic.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,620 enhanced font 'sans,11'
} else {
  set terminal png size 1100,620
}
set output 'fig4_dynamic.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 35
set xrange [0.62:20.38]
set xlabel 'frequency [Hz]' noenhanced
set ylabel 'dynamic modulus |E*| [kPa]' noenhanced
set title "|E*| (left axis) and phase (right axis) of dynamic_preload25:\ntest vs Prony fit (paper Fig. 4)" noenhanced
set y2label 'phase [deg]' noenhanced
set ytics nomirror
set y2tics
plot \
  'fig4_dynamic.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pointtype 6 pointsize 0.9 linecolor rgb '#0072B2' title '|E*| test' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#0072B2' title '|E*| Prony fit' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==2 ? $3 : 1/0) axes x1y2 with points pointtype 6 pointsize 0.9 linecolor rgb '#D55E00' title 'phase test' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==3 ? $3 : 1/0) axes x1y2 with lines linewidth 2 dashtype 2 linecolor rgb '#D55E00' title 'phase Prony fit' noenhanced
