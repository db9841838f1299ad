# Hereditary viscous stress on the paper's protocol (120 mm/min to 75 %, 2 s hold): data in table2_protocol.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'table2_protocol.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Hereditary viscous stress on the paper''s protocol (120 mm/min to 75 %, 2 s hold)' noenhanced
set xlabel 'time [s]' noenhanced
set ylabel 'viscous stress sigma_v [kPa]' noenhanced
plot \
  'table2_protocol.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with lines lw 2 title 'paper Table 2' noenhanced, \
  'table2_protocol.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'this fit' noenhanced
