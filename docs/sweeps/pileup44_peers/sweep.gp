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
set title 'pileup of 44: joint gap against cost (1 s simulated)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.215277778
set logscale xy
set xrange [0.01:10]
set yrange [1e-16:0.01]
set xtics 10
set ytics 10
set mxtics 10
set mytics 10
set format x '1e%T'
set format y '1e%T'
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'joint gap (m): largest positional joint error over the run' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key at screen 0.5, screen 0.143055556 center top vertical maxrows 5 box Left reverse width 2 noenhanced
set label 1 '2 ms' at 0.151750804, 2.20465514e-10 left font ',8' tc lt 1 front noenhanced
set label 2 '1 ms' at 0.240094139, 3.63676371e-10 left font ',8' tc lt 1 front noenhanced
set label 3 '2 ms' at 0.248249581, 5.57504143e-11 left font ',8' tc lt 2 front noenhanced
set label 4 '1 ms' at 0.320434564, 3.05246503e-10 left font ',8' tc lt 2 front noenhanced
set label 5 '0.5 ms' at 0.577627006, 2.89215953e-10 left font ',8' tc lt 2 front noenhanced
set label 6 '2 ms' at 0.319546667, 5.57503906e-11 left font ',8' tc lt 3 front noenhanced
set label 7 '0.5 ms' at 0.729687297, 8.6097841e-11 left font ',8' tc lt 3 front noenhanced
set label 8 '2 ms' at 0.171239619, 1.52591579e-15 left font ',8' tc lt 4 front noenhanced
set label 9 '1 ms' at 0.320450352, 2.21991445e-15 left font ',8' tc lt 4 front noenhanced
set label 10 '0.5 ms' at 0.760840394, 1.85760902e-15 left font ',8' tc lt 4 front noenhanced
set label 11 '2 ms' at 0.0280039861, 0.00341708592 left font ',8' tc lt 5 front noenhanced
set label 12 '1 ms' at 0.0660713003, 0.00240387976 left font ',8' tc lt 5 front noenhanced
set label 13 '0.5 ms' at 0.144897939, 0.000674742109 left font ',8' tc lt 5 front noenhanced
set label 14 '2 ms' at 0.0361984631, 0.000686814895 left font ',8' tc lt 6 front noenhanced
set label 15 '1 ms' at 0.0893563889, 0.000200033233 left font ',8' tc lt 6 front noenhanced
set label 16 '0.5 ms' at 0.229372873, 0.000284855205 left font ',8' tc lt 6 front noenhanced
set label 17 '2 ms' at 0.959330941, 0.000973719281 left font ',8' tc lt 7 front noenhanced
set label 18 '1 ms' at 1.6089019, 0.000396796473 left font ',8' tc lt 7 front noenhanced
set label 19 '0.5 ms' at 2.76585402, 0.000135432978 left font ',8' tc lt 7 front noenhanced
set label 20 '2 ms' at 0.31547708, 3.00974597e-16 left font ',8' tc lt 8 front noenhanced
set label 21 '1 ms' at 0.7179262, 2.08405528e-16 left font ',8' tc lt 8 front noenhanced
set label 22 '0.5 ms' at 1.63776044, 7.01309348e-16 left font ',8' tc lt 8 front noenhanced
set label 23 '1 ms' at 2.02512666, 2.02274607e-16 left font ',8' tc lt 9 front noenhanced
set label 24 '0.5 ms' at 4.00587578, 6.87191887e-16 left font ',8' tc lt 9 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'frontier-euler', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'frontier-rattle', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'frontier-rattle4', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'bullet-multibody', \
     data index 5 using 1:2 with linespoints lt 5 lw 2 pt 7 ps 1.2 title 'bullet-si', \
     data index 6 using 1:2 with linespoints lt 6 lw 2 pt 7 ps 1.2 title 'ode-quick', \
     data index 7 using 1:2 with linespoints lt 7 lw 2 pt 7 ps 1.2 title 'ode-direct', \
     data index 8 using 1:2 with linespoints lt 8 lw 2 pt 7 ps 1.2 title 'mujoco', \
     data index 9 using 1:2 with linespoints lt 9 lw 2 pt 7 ps 1.2 title 'mujoco-rk4'
