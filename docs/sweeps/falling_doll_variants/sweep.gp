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
set title 'falling doll: penetration against cost (1 s simulated)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.286111111
set logscale xy
set xrange [0.01:1]
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
set label 1 '0.5 ms' at 0.0714786947, 0.000540613004 left font ',8' tc lt 1 front noenhanced
set label 2 '2 ms' at 0.0302032017, 0.00145619903 left font ',8' tc lt 2 front noenhanced
set label 3 '1 ms' at 0.0375699142, 0.00119904466 left font ',8' tc lt 2 front noenhanced
set label 4 '2 ms' at 0.02456731, 0.000738459811 left font ',8' tc lt 3 front noenhanced
set label 5 '1 ms' at 0.0428226005, 0.00104518095 left font ',8' tc lt 3 front noenhanced
set label 6 '0.5 ms' at 0.0681738318, 0.000380999118 left font ',8' tc lt 3 front noenhanced
set label 7 '2 ms' at 0.0197259693, 0.00134553565 left font ',8' tc lt 4 front noenhanced
set label 8 '0.5 ms' at 0.0659949609, 0.000266931458 left font ',8' tc lt 4 front noenhanced
set label 9 '2 ms' at 0.0252034526, 0.00173540335 left font ',8' tc lt 5 front noenhanced
set label 10 '1 ms' at 0.0309429896, 0.000470921844 left font ',8' tc lt 5 front noenhanced
set label 11 '2 ms' at 0.0105698792, 0.0402788354 left font ',8' tc lt 6 front noenhanced
set label 12 '2 ms' at 0.0141802872, 0.0422332509 left font ',8' tc lt 7 front noenhanced
set label 13 '1 ms' at 0.0286054285, 0.0194523903 left font ',8' tc lt 7 front noenhanced
set label 14 '0.5 ms' at 0.0497626335, 0.0403449098 left font ',8' tc lt 7 front noenhanced
set label 15 '2 ms' at 0.0202347511, 0.0421131652 left font ',8' tc lt 8 front noenhanced
set label 16 '0.5 ms' at 0.0838303958, 0.0462064947 left font ',8' tc lt 8 front noenhanced
set label 17 '2 ms' at 0.0399144327, 0.0424946294 left font ',8' tc lt 9 front noenhanced
set label 18 '1 ms' at 0.0678989107, 0.0206120477 left font ',8' tc lt 9 front noenhanced
set label 19 '0.5 ms' at 0.14657544, 0.0430336275 left font ',8' tc lt 9 front noenhanced
set label 20 '2 ms' at 0.0107912768, 0.0133882685 left font ',8' tc lt 10 front noenhanced
set label 21 '1 ms' at 0.0169632002, 0.00483307474 left font ',8' tc lt 10 front noenhanced
set label 22 '0.5 ms' at 0.0420301602, 0.00248612476 left font ',8' tc lt 10 front noenhanced
set label 23 '2 ms' at 0.0155030426, 0.0127960317 left font ',8' tc lt 11 front noenhanced
set label 24 '1 ms' at 0.02876817, 0.00606996528 left font ',8' tc lt 11 front noenhanced
set label 25 '0.5 ms' at 0.0623064384, 0.00287772028 left font ',8' tc lt 11 front noenhanced
set label 26 '2 ms' at 0.0335349468, 0.011665504 left font ',8' tc lt 12 front noenhanced
set label 27 '1 ms' at 0.0631983518, 0.00578275506 left font ',8' tc lt 12 front noenhanced
set label 28 '0.5 ms' at 0.131543729, 0.00262824262 left font ',8' tc lt 12 front noenhanced
set label 29 '1 ms' at 0.0325889938, 0.0398172189 left font ',8' tc lt 13 front noenhanced
set label 30 '0.5 ms' at 0.0652599499, 0.0311769611 left font ',8' tc lt 13 front noenhanced
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
