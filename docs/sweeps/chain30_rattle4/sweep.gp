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
set title 'chain of 30: speed against accuracy (reference linear/rattle4 at dt 3.125e-05 s, 1 s simulated, 20 sample times)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.144444444
set logscale xy
set xrange [0.01:10]
set yrange [1e-09:0.1]
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
set label 1 '4 ms' at 0.0194321139, 0.0394773133 left font ',8' tc lt 1 front noenhanced
set label 2 '2 ms' at 0.0370466892, 0.0128017656 left font ',8' tc lt 1 front noenhanced
set label 3 '0.5 ms' at 0.165761516, 0.00490763371 left font ',8' tc lt 1 front noenhanced
set label 4 '0.25 ms' at 0.218365737, 0.00158426394 left font ',8' tc lt 1 front noenhanced
set label 5 '0.125 ms' at 0.566372295, 0.00122308885 left font ',8' tc lt 1 front noenhanced
set label 6 '4 ms' at 0.0502696036, 0.00705677335 left font ',8' tc lt 2 front noenhanced
set label 7 '2 ms' at 0.0706284317, 0.00232878057 left font ',8' tc lt 2 front noenhanced
set label 8 '1 ms' at 0.111244777, 0.000220978554 left font ',8' tc lt 2 front noenhanced
set label 9 '0.5 ms' at 0.157266749, 3.61884816e-05 left font ',8' tc lt 2 front noenhanced
set label 10 '0.25 ms' at 0.275241802, 9.07285774e-06 left font ',8' tc lt 2 front noenhanced
set label 11 '0.125 ms' at 0.832802981, 3.50822139e-06 left font ',8' tc lt 2 front noenhanced
set label 12 '4 ms' at 0.135316913, 0.0570451227 left font ',8' tc lt 3 front noenhanced
set label 13 '2 ms' at 0.214153101, 0.0329416198 left font ',8' tc lt 3 front noenhanced
set label 14 '1 ms' at 0.392640143, 0.00294022859 left font ',8' tc lt 3 front noenhanced
set label 15 '0.5 ms' at 0.469871129, 9.78172166e-07 left font ',8' tc lt 3 front noenhanced
set label 16 '0.25 ms' at 0.808625683, 3.84729029e-08 left font ',8' tc lt 3 front noenhanced
set label 17 '0.125 ms' at 2.32009617, 3.69832303e-09 left font ',8' tc lt 3 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'linear/euler', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'linear/rattle', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'linear/rattle4'
