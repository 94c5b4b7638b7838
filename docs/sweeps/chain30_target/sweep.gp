# sweep.gp: the chart of `frontier sweep`; `gnuplot sweep.gp` in this folder draws sweep.png
# from sweep.dat (the Pareto front, then one block per method).
if (!exists('out')) out = 'sweep.png'
data = 'sweep.dat'
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {
    set terminal pngcairo size 1100,720 enhanced font ',10'
} else {
    set terminal png size 1100,720 enhanced
}
set output out
set title 'chain of 30: speed against accuracy (reference rattle linear at dt 3.90625e-06 s, 1 s simulated, 20 sample times)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.144444444
set logscale xy
set xrange [0.01:10]
set yrange [1e-08:0.01]
set xtics 10
set ytics 10
set mxtics 10
set mytics 10
set format x '1e%T'
set format y '1e%T'
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'trajectory error (m): largest centre-of-mass distance to the reference' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key at screen 0.5, screen 0.0722222222 center top vertical maxrows 2 box Left reverse width 2 noenhanced
set label 1 '1 ms' at 0.0218174477, 0.00667139257 left font ',8' tc lt 1 front noenhanced
set label 2 '0.5 ms' at 0.0546389191, 0.00460462722 left font ',8' tc lt 1 front noenhanced
set label 3 '0.25 ms' at 0.101703666, 0.00229749542 left font ',8' tc lt 1 front noenhanced
set label 4 '0.125 ms' at 0.180117927, 0.00114754673 left font ',8' tc lt 1 front noenhanced
set label 5 '0.0625 ms' at 0.326490509, 0.000573473275 left font ',8' tc lt 1 front noenhanced
set label 6 '0.03125 ms' at 0.623432916, 0.000286661188 left font ',8' tc lt 1 front noenhanced
set label 7 '0.015625 ms' at 1.20774075, 0.000143311351 left font ',8' tc lt 1 front noenhanced
set label 8 '1 ms' at 0.0356018956, 0.000209267219 left font ',8' tc lt 2 front noenhanced
set label 9 '0.5 ms' at 0.0596445449, 3.82093805e-05 left font ',8' tc lt 2 front noenhanced
set label 10 '0.25 ms' at 0.104972066, 9.57692658e-06 left font ',8' tc lt 2 front noenhanced
set label 11 '0.125 ms' at 0.178860785, 2.39324213e-06 left font ',8' tc lt 2 front noenhanced
set label 12 '0.0625 ms' at 0.307891543, 5.95994935e-07 left font ',8' tc lt 2 front noenhanced
set label 13 '0.03125 ms' at 0.562569156, 1.46296947e-07 left font ',8' tc lt 2 front noenhanced
set label 14 '0.015625 ms' at 2.09082314, 4.69988086e-08 left font ',8' tc lt 2 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'euler linear', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'rattle linear'
