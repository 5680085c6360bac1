set terminal pngcairo size 900,480 font 'sans,11'
set output 'bench-results/radius_sweep.png'
set datafile separator ','
set key top left
set logscale x 2
set xlabel 'AO radius (m)'
set ylabel 'SAO pass (ms, median)'
set yrange [0:*]
set grid
set title 'SAO cost vs radius, built-in scene 1280x720'
plot 'bench-results/radius_sweep.csv' using 1:2 skip 1 with linespoints lw 2 title 'depth hierarchy on', '' using 1:3 skip 1 with linespoints lw 2 title 'depth hierarchy off'
