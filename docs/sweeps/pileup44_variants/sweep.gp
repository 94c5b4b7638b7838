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
set title 'pileup of 44: penetration against cost (1 s simulated)' noenhanced
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
set label 1 '1 ms' at 0.165104624, 0.00084505204 left font ',8' tc lt 1 front noenhanced
set label 2 '0.5 ms' at 0.311176421, 0.00044971218 left font ',8' tc lt 1 front noenhanced
set label 3 '0.5 ms' at 0.230720567, 0.000298829704 left font ',8' tc lt 2 front noenhanced
set label 4 '2 ms' at 0.063453945, 0.00169266921 left font ',8' tc lt 4 front noenhanced
set label 5 '1 ms' at 0.0793784114, 0.000847801707 left font ',8' tc lt 5 front noenhanced
set label 6 '0.5 ms' at 0.157901503, 0.000392781928 left font ',8' tc lt 5 front noenhanced
set label 7 '2 ms' at 0.0281677402, 0.0104712497 left font ',8' tc lt 6 front noenhanced
set label 8 '1 ms' at 0.0439937745, 0.00310288251 left font ',8' tc lt 6 front noenhanced
set label 9 '2 ms' at 0.0425551383, 0.0114609112 left font ',8' tc lt 7 front noenhanced
set label 10 '0.5 ms' at 0.196092123, 0.00102653372 left font ',8' tc lt 7 front noenhanced
set label 11 '2 ms' at 0.0652983678, 0.0090877253 left font ',8' tc lt 8 front noenhanced
set label 12 '0.5 ms' at 0.2662374, 0.00115273211 left font ',8' tc lt 8 front noenhanced
set label 13 '2 ms' at 0.120201772, 0.00848702517 left font ',8' tc lt 9 front noenhanced
set label 14 '1 ms' at 0.196789726, 0.00293263295 left font ',8' tc lt 9 front noenhanced
set label 15 '0.5 ms' at 0.472762889, 0.0013492641 left font ',8' tc lt 9 front noenhanced
set label 16 '1 ms' at 0.0641300287, 0.00444835231 left font ',8' tc lt 10 front noenhanced
set label 17 '1 ms' at 0.0979152458, 0.00466233439 left font ',8' tc lt 11 front noenhanced
set label 18 '0.5 ms' at 0.237917329, 0.0024098125 left font ',8' tc lt 11 front noenhanced
set label 19 '2 ms' at 0.0920039362, 0.00872847084 left font ',8' tc lt 12 front noenhanced
set label 20 '1 ms' at 0.191763358, 0.00456945456 left font ',8' tc lt 12 front noenhanced
set label 21 '0.5 ms' at 0.466628822, 0.00219890411 left font ',8' tc lt 12 front noenhanced
set label 22 '2 ms' at 0.390357483, 0.0378219998 left font ',8' tc lt 13 front noenhanced
set label 23 '1 ms' at 0.447520403, 0.02938491 left font ',8' tc lt 13 front noenhanced
set label 24 '0.5 ms' at 1.39124209, 0.0412802769 left font ',8' tc lt 13 front noenhanced
set label 25 '2 ms' at 0.285326247, 0.0374271689 left font ',8' tc lt 14 front noenhanced
set label 26 '1 ms' at 0.571359659, 0.0402805104 left font ',8' tc lt 14 front noenhanced
set label 27 '0.5 ms' at 1.79696107, 0.0307107294 left font ',8' tc lt 14 front noenhanced
set label 28 '2 ms' at 0.338595615, 0.0280310401 left font ',8' tc lt 15 front noenhanced
set label 29 '1 ms' at 0.726236805, 0.0402805104 left font ',8' tc lt 15 front noenhanced
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
