# Gramicidin A pore radius profiles (vorball channels, 256^3, probe 1.0 A):
#   gnuplot -e "bondi='grm_bondi.tsv'; hole='grm_hole.tsv'; out='grm_profile.png'" profile.gp
set terminal pngcairo size 900,500 noenhanced
set output out
set xlabel "position along the pore axis y (A)"
set ylabel "clearance radius (A)"
set yrange [0:6]
set grid
set key top center
set arrow from graph 0, first 1.15 to graph 1, first 1.15 nohead dt 2 lc rgb "gray40"
set label "HOLE minimum ~1.15 A" at graph 0.02, first 1.35 tc rgb "gray30"
plot bondi using 1:2 with linespoints pt 7 ps 0.4 title "Bondi radii (C 1.70, N 1.55, O 1.52)", \
     hole using 1:2 with linespoints pt 5 ps 0.4 title "HOLE simple.rad radii (C 1.85, N 1.75, O 1.65)"
