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
set logscale xy
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'trajectory error (m): largest centre-of-mass distance to the reference' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set format xy '%g'
set key below box Left reverse noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'euler linear', \
     data index 1 using 1:2:3 with labels left offset char 0.6,0.6 font ',8' tc lt 1 notitle, \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'rattle linear', \
     data index 2 using 1:2:3 with labels left offset char 0.6,0.6 font ',8' tc lt 2 notitle
