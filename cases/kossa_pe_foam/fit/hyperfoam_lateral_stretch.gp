# Stretch of the stress-free direction: measured vs fitted: data in hyperfoam_lateral_stretch.csv (series,x,y; series numbered below)
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
  set terminal pngcairo size 900,600 enhanced font 'sans,11'
} else {
  set terminal png size 900,600
}
set output 'hyperfoam_lateral_stretch.png'
set datafile separator comma
set key outside bottom center horizontal
set grid
set title 'Stretch of the stress-free direction: measured vs fitted' noenhanced
set xlabel 'loaded stretch [-]' noenhanced
set ylabel 'lateral stretch [-]' noenhanced
plot \
  'hyperfoam_lateral_stretch.csv' skip 1 using 2:($1==0 ? $3 : 1/0) with points pt 7 ps 0.6 title 'uniaxial measured' noenhanced, \
  'hyperfoam_lateral_stretch.csv' skip 1 using 2:($1==1 ? $3 : 1/0) with lines lw 2 title 'uniaxial fitted' noenhanced, \
  'hyperfoam_lateral_stretch.csv' skip 1 using 2:($1==2 ? $3 : 1/0) with points pt 7 ps 0.6 title 'equibiaxial measured' noenhanced, \
  'hyperfoam_lateral_stretch.csv' skip 1 using 2:($1==3 ? $3 : 1/0) with lines lw 2 title 'equibiaxial fitted' noenhanced
