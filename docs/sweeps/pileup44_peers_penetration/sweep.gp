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
set title 'pileup of 44: penetration against cost (1 s simulated)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.215277778
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
set key at screen 0.5, screen 0.143055556 center top vertical maxrows 5 box Left reverse width 2 noenhanced
set label 1 '1 ms' at 0.19028333, 0.000669658755 left font ',8' tc lt 1 front noenhanced
set label 2 '0.5 ms' at 0.289358291, 0.000477995687 left font ',8' tc lt 1 front noenhanced
set label 3 '2 ms' at 0.191069637, 0.00296944294 left font ',8' tc lt 2 front noenhanced
set label 4 '1 ms' at 0.32552524, 0.00123271233 left font ',8' tc lt 2 front noenhanced
set label 5 '0.5 ms' at 0.378546334, 0.000548357769 left font ',8' tc lt 2 front noenhanced
set label 6 '2 ms' at 0.255070727, 0.00321779747 left font ',8' tc lt 3 front noenhanced
set label 7 '1 ms' at 0.469840502, 0.00146327195 left font ',8' tc lt 3 front noenhanced
set label 8 '0.5 ms' at 0.610460337, 0.000547877266 left font ',8' tc lt 3 front noenhanced
set label 9 '2 ms' at 0.201024908, 0.0152041377 left font ',8' tc lt 4 front noenhanced
set label 10 '1 ms' at 0.397828237, 0.00208555172 left font ',8' tc lt 4 front noenhanced
set label 11 '0.5 ms' at 0.727719473, 0.00161857 left font ',8' tc lt 4 front noenhanced
set label 12 '2 ms' at 0.0288140684, 0.0127879889 left font ',8' tc lt 5 front noenhanced
set label 13 '1 ms' at 0.0626057297, 0.00292881826 left font ',8' tc lt 5 front noenhanced
set label 14 '0.5 ms' at 0.102357068, 0.00103617199 left font ',8' tc lt 5 front noenhanced
set label 15 '2 ms' at 0.0391953388, 0.00667713857 left font ',8' tc lt 6 front noenhanced
set label 16 '1 ms' at 0.111924731, 0.00489886428 left font ',8' tc lt 6 front noenhanced
set label 17 '0.5 ms' at 0.189923009, 0.00223386729 left font ',8' tc lt 6 front noenhanced
set label 18 '2 ms' at 0.709099109, 0.00783318102 left font ',8' tc lt 7 front noenhanced
set label 19 '1 ms' at 1.60629157, 0.00478262759 left font ',8' tc lt 7 front noenhanced
set label 20 '0.5 ms' at 2.5481124, 0.00199686824 left font ',8' tc lt 7 front noenhanced
set label 21 '2 ms' at 0.291004759, 0.031797111 left font ',8' tc lt 8 front noenhanced
set label 22 '1 ms' at 0.695350591, 0.0360397561 left font ',8' tc lt 8 front noenhanced
set label 23 '0.5 ms' at 1.21360617, 0.0280091748 left font ',8' tc lt 8 front noenhanced
set label 24 '2 ms' at 1.18828246, 0.0371535999 left font ',8' tc lt 9 front noenhanced
set label 25 '1 ms' at 1.62318642, 0.0378057313 left font ',8' tc lt 9 front noenhanced
set label 26 '0.5 ms' at 3.72108224, 0.0340395587 left font ',8' tc lt 9 front noenhanced
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
