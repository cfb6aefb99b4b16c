# The Facet-JFA speed-up figure (paper Fig. 4): time of JFA+1 over time of
# Facet-JFA against the number of seeds, one line per grid size.
#   gnuplot -e "dir='results/jfa'; device='NVIDIA H200'" jfa_speedup.gp
if (!exists("dir")) dir = 'results/jfa'
if (!exists("device")) device = ''
set terminal pngcairo size 900,600 noenhanced
set output dir.'/jfa_speedup.png'
set logscale x
set xlabel 'seeds'
set ylabel 'speed-up over JFA+1'
set title 'Facet-JFA and exact speed-up, 2D, uniform seeds ('.device.')'
set key top right
set grid
set yrange [0:*]
f(x) = 1
# Solid: Facet-JFA over JFA+1; dashed: the exact engine over JFA+1 (column
# 10; rows without an exact run have 0 there and are left out).
plot for [i=0:4] dir.'/jfa_speedup.dat' index i using 2:5 with linespoints \
       title sprintf('%d^2 Facet-JFA', 256 * 2**i), \
     for [i=0:4] dir.'/jfa_speedup.dat' index i using 2:($10 > 0 ? $10 : 1/0) \
       with linespoints dashtype 3 title sprintf('%d^2 exact', 256 * 2**i), \
     f(x) with lines dashtype 2 lc rgb 'black' title 'no speed-up'
