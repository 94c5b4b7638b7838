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
set title 'chain of 30: speed against accuracy (reference rattle linear at dt 3.125e-05 s, 1 s simulated, 20 sample times)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.191666667
set logscale xy
set xrange [0.01:100]
set yrange [1e-06:0.1]
set xtics 10
set ytics 10
set mxtics 10
set mytics 10
set format x '1e%T'
set format y '1e%T'
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'trajectory error (m): largest centre-of-mass distance to the reference' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key at screen 0.5, screen 0.119444444 center top vertical maxrows 4 box Left reverse width 2 noenhanced
set label 1 '2 ms' at 0.0125644725, 0.0182353726 left font ',8' tc lt 1 front noenhanced
set label 2 '1 ms' at 0.033502695, 0.00907944863 left font ',8' tc lt 1 front noenhanced
set label 3 '0.5 ms' at 0.0609425252, 0.00452064738 left font ',8' tc lt 1 front noenhanced
set label 4 '0.25 ms' at 0.110898886, 0.00225556209 left font ',8' tc lt 1 front noenhanced
set label 5 '0.125 ms' at 0.19899431, 0.00112657074 left font ',8' tc lt 1 front noenhanced
set label 6 '2 ms' at 0.320414043, 0.0597840438 left font ',8' tc lt 2 front noenhanced
set label 7 '1 ms' at 0.665936251, 0.0224038776 left font ',8' tc lt 2 front noenhanced
set label 8 '0.5 ms' at 1.17089916, 0.0120960055 left font ',8' tc lt 2 front noenhanced
set label 9 '0.25 ms' at 2.12683245, 0.00661632906 left font ',8' tc lt 2 front noenhanced
set label 10 '0.125 ms' at 3.90887436, 0.00352115382 left font ',8' tc lt 2 front noenhanced
set label 11 '2 ms' at 1.06645177, 0.0294010439 left font ',8' tc lt 3 front noenhanced
set label 12 '0.125 ms' at 7.35563749, 0.0015588263 left font ',8' tc lt 3 front noenhanced
set label 13 '2 ms' at 0.0201196687, 0.00334655781 left font ',8' tc lt 4 front noenhanced
set label 14 '1 ms' at 0.0359556163, 0.000205254308 left font ',8' tc lt 4 front noenhanced
set label 15 '0.5 ms' at 0.0584418441, 3.87696439e-05 left font ',8' tc lt 4 front noenhanced
set label 16 '0.25 ms' at 0.102168186, 9.60568931e-06 left font ',8' tc lt 4 front noenhanced
set label 17 '0.125 ms' at 0.345983548, 3.0580069e-06 left font ',8' tc lt 4 front noenhanced
set label 18 '2 ms' at 0.516429536, 0.0597840438 left font ',8' tc lt 5 front noenhanced
set label 19 '0.125 ms' at 8.2118303, 0.00470405016 left font ',8' tc lt 5 front noenhanced
set label 20 '2 ms' at 1.75225596, 0.0294010439 left font ',8' tc lt 6 front noenhanced
set label 21 '1 ms' at 3.18678969, 0.014490504 left font ',8' tc lt 6 front noenhanced
set label 22 '0.5 ms' at 5.42233225, 0.00763822709 left font ',8' tc lt 6 front noenhanced
set label 23 '0.125 ms' at 15.136529, 0.00207245807 left font ',8' tc lt 6 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'euler linear', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'euler pgs:20', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'euler pgs:100', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'rattle linear', \
     data index 5 using 1:2 with linespoints lt 5 lw 2 pt 7 ps 1.2 title 'rattle pgs:20', \
     data index 6 using 1:2 with linespoints lt 6 lw 2 pt 7 ps 1.2 title 'rattle pgs:100'
