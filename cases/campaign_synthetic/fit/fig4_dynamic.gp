# Dynamic modulus and phase of dynamic_preload25 (paper Fig. 4): data in fig4_dynamic.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'fig4_dynamic.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Dynamic modulus and phase of dynamic_preload25 (paper Fig. 4)' noenhanced
set xlabel 'frequency [Hz]' noenhanced
set ylabel 'dynamic modulus |E*| [kPa]' noenhanced
set y2label 'phase [deg]' noenhanced
set ytics nomirror
set y2tics
plot \
  'fig4_dynamic.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title '|E*| test' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title '|E*| Prony fit' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==2 ? $3 : 1/0) axes x1y2 with points pt 7 ps 0.6 title 'phase test' noenhanced, \
  'fig4_dynamic.csv' skip 1 using 2:($1==3 ? $3 : 1/0) axes x1y2 with lines lw 2 title 'phase Prony fit' noenhanced
