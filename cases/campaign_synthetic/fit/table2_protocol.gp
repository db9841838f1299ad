# Viscous stress on the paper's protocol (120 mm/min to 75 %, 2 s hold): paper Table 2 modes vs this fit's modes: data in table2_protocol.csv (series,x,y; series numbered below)
reset
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 1100,620 enhanced font 'sans,11'
} else {
  set terminal png size 1100,620
}
set output 'table2_protocol.png'
set datafile separator comma
set key outside right top vertical Left reverse noenhanced
set grid
set lmargin 12
set rmargin 23
set xrange [-1.24:63.24]
set xlabel 'time [s]' noenhanced
set ylabel 'viscous stress sigma_v [kPa]' noenhanced
set title "Viscous stress on the paper's protocol (120 mm/min to 75 %, 2 s hold):\npaper Table 2 modes vs this fit's modes" noenhanced
plot \
  'table2_protocol.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with lines linewidth 2 dashtype 1 linecolor rgb '#0072B2' title 'paper Table 2' noenhanced, \
  'table2_protocol.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines linewidth 2 dashtype 2 linecolor rgb '#D55E00' title 'this fit' noenhanced
