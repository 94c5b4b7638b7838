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
set title 'chain of 30: speed against accuracy (reference linear/rattle at dt 5e-06 s, 1 s simulated, 1 sample time)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.191666667
set logscale xy
set xrange [0.001:10]
set yrange [1e-09:1]
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
set label 1 '4 ms' at 0.00697025206, 0.0181334987 left font ',8' tc lt 1 front noenhanced
set label 2 '2 ms' at 0.0115572594, 0.00553849942 left font ',8' tc lt 1 front noenhanced
set label 3 '1 ms' at 0.0204849136, 0.00291855601 left font ',8' tc lt 1 front noenhanced
set label 4 '0.25 ms' at 0.060740265, 0.000721261035 left font ',8' tc lt 1 front noenhanced
set label 5 '1 ms' at 0.0370964949, 0.000136933535 left font ',8' tc lt 2 front noenhanced
set label 6 '0.5 ms' at 0.0607526869, 3.46582019e-05 left font ',8' tc lt 2 front noenhanced
set label 7 '0.25 ms' at 0.109203441, 8.6863353e-06 left font ',8' tc lt 2 front noenhanced
set label 8 '0.125 ms' at 0.390736114, 3.6562774e-06 left font ',8' tc lt 2 front noenhanced
set label 9 '4 ms' at 0.0560620761, 0.0595572895 left font ',8' tc lt 3 front noenhanced
set label 10 '2 ms' at 0.100554687, 0.0343923089 left font ',8' tc lt 3 front noenhanced
set label 11 '1 ms' at 0.181607385, 0.00304944993 left font ',8' tc lt 3 front noenhanced
set label 12 '0.5 ms' at 0.18933173, 9.74256029e-07 left font ',8' tc lt 3 front noenhanced
set label 13 '0.25 ms' at 0.334756379, 3.90199519e-08 left font ',8' tc lt 3 front noenhanced
set label 14 '0.125 ms' at 0.57082914, 6.0237293e-09 left font ',8' tc lt 3 front noenhanced
set label 15 '4 ms' at 0.00420070566, 0.178113054 left font ',8' tc lt 4 front noenhanced
set label 16 '2 ms' at 0.0120256386, 0.0627449421 left font ',8' tc lt 4 front noenhanced
set label 17 '1 ms' at 0.023560374, 0.0910547108 left font ',8' tc lt 4 front noenhanced
set label 18 '0.5 ms' at 0.0283847129, 0.175874234 left font ',8' tc lt 4 front noenhanced
set label 19 '0.25 ms' at 0.0744926133, 0.236737807 left font ',8' tc lt 4 front noenhanced
set label 20 '0.125 ms' at 0.181505304, 0.193348299 left font ',8' tc lt 4 front noenhanced
set label 21 '2 ms' at 0.0239366441, 0.0178847626 left font ',8' tc lt 5 front noenhanced
set label 22 '0.5 ms' at 0.0956973865, 0.00189223704 left font ',8' tc lt 5 front noenhanced
set label 23 '0.25 ms' at 0.186014187, 0.00103264468 left font ',8' tc lt 5 front noenhanced
set label 24 '0.125 ms' at 0.359600169, 0.000569430279 left font ',8' tc lt 5 front noenhanced
set label 25 '4 ms' at 0.0167503154, 0.590473311 left font ',8' tc lt 6 front noenhanced
set label 26 '2 ms' at 0.0472780602, 0.301712408 left font ',8' tc lt 6 front noenhanced
set label 27 '1 ms' at 0.0832229916, 0.0626603484 left font ',8' tc lt 6 front noenhanced
set label 28 '0.5 ms' at 0.200308932, 0.0631203986 left font ',8' tc lt 6 front noenhanced
set label 29 '0.25 ms' at 0.400347272, 0.0307643196 left font ',8' tc lt 6 front noenhanced
set label 30 '0.125 ms' at 0.796939939, 0.0151927186 left font ',8' tc lt 6 front noenhanced
set label 31 '4 ms' at 0.100512513, 0.000524269825 left font ',8' tc lt 7 front noenhanced
set label 32 '1 ms' at 0.396831866, 1.46464075e-06 left font ',8' tc lt 7 front noenhanced
set label 33 '0.5 ms' at 0.791278505, 9.35227734e-08 left font ',8' tc lt 7 front noenhanced
set label 34 '0.25 ms' at 2.13858042, 1.18815324e-08 left font ',8' tc lt 7 front noenhanced
set label 35 '0.125 ms' at 3.37196524, 6.80431829e-09 left font ',8' tc lt 7 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'frontier-euler', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'frontier-rattle', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'frontier-rattle4', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'bullet-multibody', \
     data index 5 using 1:2 with linespoints lt 5 lw 2 pt 7 ps 1.2 title 'ode-direct', \
     data index 6 using 1:2 with linespoints lt 6 lw 2 pt 7 ps 1.2 title 'mujoco', \
     data index 7 using 1:2 with linespoints lt 7 lw 2 pt 7 ps 1.2 title 'mujoco-rk4'
