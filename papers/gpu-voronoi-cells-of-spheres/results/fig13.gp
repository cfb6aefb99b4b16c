set terminal pngcairo size 1200,500 noenhanced
set output "results/fig13.png"
set multiplot layout 1,2
set key bottom right
set xlabel 'samples S (S x S per face)'
set title 'first cell (sphere 0): vertices found by sampling'
set ylabel 'vertices'
plot 'results/fig13.dat' index 0 using 2:3 with linespoints title '1crn', 'results/fig13.dat' index 1 using 2:3 with linespoints title '1crn_apbs', 'results/fig13.dat' index 2 using 2:3 with linespoints title '1grm_single_hole2', 'results/fig13.dat' index 3 using 2:3 with linespoints title '3pqr'
set title 'whole diagram: from sampling / certified'
set logscale y
plot 'results/fig13.dat' index 0 using 2:4 with linespoints title '1crn sampled', 'results/fig13.dat' index 0 using 2:5 with lines dashtype 2 title '1crn certified', 'results/fig13.dat' index 1 using 2:4 with linespoints title '1crn_apbs sampled', 'results/fig13.dat' index 1 using 2:5 with lines dashtype 2 title '1crn_apbs certified', 'results/fig13.dat' index 2 using 2:4 with linespoints title '1grm_single_hole2 sampled', 'results/fig13.dat' index 2 using 2:5 with lines dashtype 2 title '1grm_single_hole2 certified', 'results/fig13.dat' index 3 using 2:4 with linespoints title '3pqr sampled', 'results/fig13.dat' index 3 using 2:5 with lines dashtype 2 title '3pqr certified'
unset multiplot
