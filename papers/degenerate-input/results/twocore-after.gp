set terminal pngcairo size 1100,850 font ',9'
set output 'twocore-after.png'
set termoption noenhanced
set multiplot layout 2,2 title "twocore-after: machine twocore-after: 2 CPUs, Intel(R) Xeon(R) Processor; 2026-12-02T15:02Z; load 1.04 1.65 1.74 (open circles: past the time limit)"
set logscale xy
set xlabel 'balls'
set ylabel 'wall time (s)'
set grid
set key top left font ',7'
set title 'fcc'
set xrange [300:20000]
set autoscale y
plot 'twocore-after.plotdata' index 0 using 1:($3==0?$2:1/0) with linespoints lc 1 pt 7 ps 0.6 title 'exact', 'twocore-after.plotdata' index 0 using 1:($3==1?$2:1/0) with points lc 1 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 1 using 1:($3==0?$2:1/0) with linespoints lc 2 pt 7 ps 0.6 title 'j1e-12', 'twocore-after.plotdata' index 1 using 1:($3==1?$2:1/0) with points lc 2 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 2 using 1:($3==0?$2:1/0) with linespoints lc 3 pt 7 ps 0.6 title 'j1e-9', 'twocore-after.plotdata' index 2 using 1:($3==1?$2:1/0) with points lc 3 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 3 using 1:($3==0?$2:1/0) with linespoints lc 4 pt 7 ps 0.6 title 'j1e-6', 'twocore-after.plotdata' index 3 using 1:($3==1?$2:1/0) with points lc 4 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 4 using 1:($3==0?$2:1/0) with linespoints lc 5 pt 7 ps 0.6 title 'j1e-3', 'twocore-after.plotdata' index 4 using 1:($3==1?$2:1/0) with points lc 5 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 5 using 1:($3==0?$2:1/0) with linespoints lc 6 pt 7 ps 0.6 title 'random', 'twocore-after.plotdata' index 5 using 1:($3==1?$2:1/0) with points lc 6 pt 6 ps 1 notitle
set title 'bcc'
set xrange [300:20000]
set autoscale y
plot 'twocore-after.plotdata' index 6 using 1:($3==0?$2:1/0) with linespoints lc 1 pt 7 ps 0.6 title 'exact', 'twocore-after.plotdata' index 6 using 1:($3==1?$2:1/0) with points lc 1 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 7 using 1:($3==0?$2:1/0) with linespoints lc 2 pt 7 ps 0.6 title 'j1e-12', 'twocore-after.plotdata' index 7 using 1:($3==1?$2:1/0) with points lc 2 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 8 using 1:($3==0?$2:1/0) with linespoints lc 3 pt 7 ps 0.6 title 'j1e-9', 'twocore-after.plotdata' index 8 using 1:($3==1?$2:1/0) with points lc 3 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 9 using 1:($3==0?$2:1/0) with linespoints lc 4 pt 7 ps 0.6 title 'j1e-6', 'twocore-after.plotdata' index 9 using 1:($3==1?$2:1/0) with points lc 4 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 10 using 1:($3==0?$2:1/0) with linespoints lc 5 pt 7 ps 0.6 title 'j1e-3', 'twocore-after.plotdata' index 10 using 1:($3==1?$2:1/0) with points lc 5 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 11 using 1:($3==0?$2:1/0) with linespoints lc 6 pt 7 ps 0.6 title 'random', 'twocore-after.plotdata' index 11 using 1:($3==1?$2:1/0) with points lc 6 pt 6 ps 1 notitle
set title 'sc'
set xrange [300:20000]
set autoscale y
plot 'twocore-after.plotdata' index 12 using 1:($3==0?$2:1/0) with linespoints lc 1 pt 7 ps 0.6 title 'exact', 'twocore-after.plotdata' index 12 using 1:($3==1?$2:1/0) with points lc 1 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 13 using 1:($3==0?$2:1/0) with linespoints lc 2 pt 7 ps 0.6 title 'j1e-12', 'twocore-after.plotdata' index 13 using 1:($3==1?$2:1/0) with points lc 2 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 14 using 1:($3==0?$2:1/0) with linespoints lc 3 pt 7 ps 0.6 title 'j1e-9', 'twocore-after.plotdata' index 14 using 1:($3==1?$2:1/0) with points lc 3 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 15 using 1:($3==0?$2:1/0) with linespoints lc 4 pt 7 ps 0.6 title 'j1e-6', 'twocore-after.plotdata' index 15 using 1:($3==1?$2:1/0) with points lc 4 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 16 using 1:($3==0?$2:1/0) with linespoints lc 5 pt 7 ps 0.6 title 'j1e-3', 'twocore-after.plotdata' index 16 using 1:($3==1?$2:1/0) with points lc 5 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 17 using 1:($3==0?$2:1/0) with linespoints lc 6 pt 7 ps 0.6 title 'random', 'twocore-after.plotdata' index 17 using 1:($3==1?$2:1/0) with points lc 6 pt 6 ps 1 notitle
set title 'Song 2022 and cospherical'
set autoscale x
set autoscale y
plot 'twocore-after.plotdata' index 18 using 1:($3==0?$2:1/0) with points lc 1 pt 7 ps 0.6 title 'EXTREMESET', 'twocore-after.plotdata' index 18 using 1:($3==1?$2:1/0) with points lc 1 pt 6 ps 1 notitle, 'twocore-after.plotdata' index 19 using 1:($3==0?$2:1/0) with points lc 2 pt 7 ps 0.6 title 'cospherical', 'twocore-after.plotdata' index 19 using 1:($3==1?$2:1/0) with points lc 2 pt 6 ps 1 notitle
unset multiplot
