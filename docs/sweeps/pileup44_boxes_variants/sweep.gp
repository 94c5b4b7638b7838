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
set linetype 9 lc rgb '#8c564b'
set linetype 10 lc rgb '#7f7f7f'
set linetype 11 lc rgb '#bcbd22'
set linetype 12 lc rgb '#17becf'
set linetype 13 lc rgb '#e377c2'
set linetype 14 lc rgb '#393b79'
set linetype 15 lc rgb '#637939'
set linetype 16 lc rgb '#ad494a'
set title 'box pileup of 44: penetration against cost (3 s simulated)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.286111111
set logscale xy
set xrange [0.01:10]
set yrange [0.0001:0.1]
set xtics 10
set ytics 10
set mxtics 10
set mytics 10
set format x '1e%T'
set format y '1e%T'
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'penetration (m): deepest contact overlap over the run' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key at screen 0.5, screen 0.213888889 center top vertical maxrows 8 box Left reverse width 2 noenhanced
set label 1 '2 ms' at 0.215312386, 0.00188355418 left font ',8' tc lt 1 front noenhanced
set label 2 '0.5 ms' at 0.291475031, 0.000407746691 left font ',8' tc lt 1 front noenhanced
set label 3 '1 ms' at 0.0942601358, 0.00100011613 left font ',8' tc lt 2 front noenhanced
set label 4 '0.5 ms' at 0.24462725, 0.000534844312 left font ',8' tc lt 2 front noenhanced
set label 5 '0.5 ms' at 0.147874623, 0.000459317883 left font ',8' tc lt 3 front noenhanced
set label 6 '2 ms' at 0.0743881382, 0.00456144337 left font ',8' tc lt 4 front noenhanced
set label 7 '1 ms' at 0.127299921, 0.0020783435 left font ',8' tc lt 4 front noenhanced
set label 8 '2 ms' at 0.0504264802, 0.00282403132 left font ',8' tc lt 5 front noenhanced
set label 9 '0.5 ms' at 0.150243821, 0.000375830045 left font ',8' tc lt 5 front noenhanced
set label 10 '2 ms' at 0.029853938, 0.0200098519 left font ',8' tc lt 6 front noenhanced
set label 11 '0.5 ms' at 0.113609394, 0.00298276596 left font ',8' tc lt 6 front noenhanced
set label 12 '2 ms' at 0.0547585587, 0.0204746457 left font ',8' tc lt 7 front noenhanced
set label 13 '1 ms' at 0.102318613, 0.00819291021 left font ',8' tc lt 7 front noenhanced
set label 14 '2 ms' at 0.0834149387, 0.0194148812 left font ',8' tc lt 8 front noenhanced
set label 15 '0.5 ms' at 0.334132804, 0.00301234337 left font ',8' tc lt 8 front noenhanced
set label 16 '2 ms' at 0.161245144, 0.0196629228 left font ',8' tc lt 9 front noenhanced
set label 17 '1 ms' at 0.303289926, 0.00806324612 left font ',8' tc lt 9 front noenhanced
set label 18 '0.5 ms' at 0.660359805, 0.00337934564 left font ',8' tc lt 9 front noenhanced
set label 19 '2 ms' at 0.039934523, 0.00917708024 left font ',8' tc lt 10 front noenhanced
set label 20 '1 ms' at 0.0927392786, 0.00408288249 left font ',8' tc lt 10 front noenhanced
set label 21 '0.5 ms' at 0.23100286, 0.00227354209 left font ',8' tc lt 10 front noenhanced
set label 22 '0.5 ms' at 0.340813753, 0.00213850183 left font ',8' tc lt 11 front noenhanced
set label 23 '2 ms' at 0.175296039, 0.0101827656 left font ',8' tc lt 12 front noenhanced
set label 24 '1 ms' at 0.289915666, 0.00378852182 left font ',8' tc lt 12 front noenhanced
set label 25 '0.5 ms' at 0.712673774, 0.00238355831 left font ',8' tc lt 12 front noenhanced
set label 26 '2 ms' at 0.482276445, 0.0397373471 left font ',8' tc lt 13 front noenhanced
set label 27 '1 ms' at 0.596870207, 0.0297948832 left font ',8' tc lt 13 front noenhanced
set label 28 '0.5 ms' at 1.35123702, 0.0409623719 left font ',8' tc lt 13 front noenhanced
set label 29 '2 ms' at 0.344868935, 0.0369888832 left font ',8' tc lt 14 front noenhanced
set label 30 '1 ms' at 0.764185434, 0.0406000555 left font ',8' tc lt 14 front noenhanced
set label 31 '0.5 ms' at 1.69576724, 0.0306054642 left font ',8' tc lt 14 front noenhanced
set label 32 '2 ms' at 0.348464632, 0.0302904151 left font ',8' tc lt 15 front noenhanced
set label 33 '1 ms' at 0.769301963, 0.0278097504 left font ',8' tc lt 15 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'frontier-euler:relative=0', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'frontier-euler:relative=1e-3', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'frontier-euler:relative=1e-2', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'frontier-euler:relative=1e-1', \
     data index 5 using 1:2 with linespoints lt 5 lw 2 pt 7 ps 1.2 title 'frontier-euler:tolerance=1e-3', \
     data index 6 using 1:2 with linespoints lt 6 lw 2 pt 7 ps 1.2 title 'bullet-si:iterations=5', \
     data index 7 using 1:2 with linespoints lt 7 lw 2 pt 7 ps 1.2 title 'bullet-si:iterations=10', \
     data index 8 using 1:2 with linespoints lt 8 lw 2 pt 7 ps 1.2 title 'bullet-si:iterations=20', \
     data index 9 using 1:2 with linespoints lt 9 lw 2 pt 7 ps 1.2 title 'bullet-si:iterations=50', \
     data index 10 using 1:2 with linespoints lt 10 lw 2 pt 7 ps 1.2 title 'ode-quick:iterations=10', \
     data index 11 using 1:2 with linespoints lt 11 lw 2 pt 7 ps 1.2 title 'ode-quick:iterations=20', \
     data index 12 using 1:2 with linespoints lt 12 lw 2 pt 7 ps 1.2 title 'ode-quick:iterations=50', \
     data index 13 using 1:2 with linespoints lt 13 lw 2 pt 7 ps 1.2 title 'mujoco:iterations=5', \
     data index 14 using 1:2 with linespoints lt 14 lw 2 pt 7 ps 1.2 title 'mujoco:iterations=100', \
     data index 15 using 1:2 with linespoints lt 15 lw 2 pt 7 ps 1.2 title 'mujoco:iterations=1000:tolerance=1e-12'
