# Nominal stress: measured vs fitted hyperfoam: data in hyperfoam_stress.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'hyperfoam_stress.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Nominal stress: measured vs fitted hyperfoam' noenhanced
set xlabel 'stretch (simple shear: gamma) [-]' noenhanced
set ylabel 'nominal stress [MPa] (tension positive)' noenhanced
plot \
  'hyperfoam_stress.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'uniaxial measured' noenhanced, \
  'hyperfoam_stress.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'uniaxial fitted' noenhanced, \
  'hyperfoam_stress.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with points pt 7 ps 0.6 title 'equibiaxial measured' noenhanced, \
  'hyperfoam_stress.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with lines lw 2 title 'equibiaxial fitted' noenhanced
