# Time and peak host memory against atoms, log-log: gnuplot scaling_h200.gp (writes scaling_h200.png)
set terminal pngcairo size 1100,450 font ",10"
set output "scaling_h200.png"
set datafile missing "NaN"
set logscale xy
set grid
set key left top
set multiplot layout 1,2 title "EV71 capsid and its tilings, NVIDIA H200 (16 host cores)"
set xlabel "atoms"
set ylabel "seconds"
plot "scaling_h200.tsv" u 1:2 w lp pt 7 t "vorball bench (cover + certification)", \
     "" u 1:3 w lp pt 6 t "vorball process (read, compute, write)", \
     "" u 1:5 w lp pt 5 t "apo build() (TOG 2025, not exact)", \
     "" u 1:6 w lp pt 4 t "Voronota 1.29, 16 threads"
set ylabel "peak host RSS (MiB)"
plot "scaling_h200.tsv" u 1:4 w lp pt 7 t "vorball", \
     "" u 1:7 w lp pt 4 t "Voronota 1.29, 16 threads"
unset multiplot
