# The strong-scaling table of strong_scaling.sh as a plot: efficiency against
# ranks for the vertices (ranks x threads fixed: ideal 1) and the channels
# (one core a rank: ideal 1 too, as speedup / ranks).
# usage: gnuplot -e "tsv='results/scaling.tsv'; png='results/scaling.png'" scaling.gp
if (!exists("tsv")) tsv = 'results/scaling.tsv'
if (!exists("png")) png = 'results/scaling.png'
set terminal pngcairo size 720,480 font ",11"
set output png
set datafile separator "\t"
set key bottom left
set logscale x 2
set xlabel "MPI ranks"
set ylabel "parallel efficiency"
set yrange [0:1.25]
set grid
set title "vorball over MPI ranks: 211,440-atom capsid (vertices), 500-frame trajectory (channels)"
plot tsv using (strcol(1) eq "vertices" ? $2 : NaN):6 with linespoints lw 2 pt 7 \
         title "vertices (ranks x threads = cores)", \
     tsv using (strcol(1) eq "channels" ? $2 : NaN):6 with linespoints lw 2 pt 5 \
         title "channels (one core a rank)", \
     1 with lines dt 2 lc rgb "gray" title "ideal"
