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
set title 'pileup of 44: speed against accuracy (reference rattle linear at dt 0.000125 s, 1 s simulated, 20 sample times)' . "\n" . '(chaotic: error does not rank the methods; no method''s error falls as dt is refined)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.168055556
set logscale xy
set xrange [0.1:10]
set yrange [0.01:1]
set xtics 10
set ytics 10
set mxtics 10
set mytics 10
set format x '1e%T'
set format y '1e%T'
set xlabel 'cost: wall seconds per simulated second' noenhanced
set ylabel 'trajectory error (m): largest centre-of-mass distance to the reference' noenhanced
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set key at screen 0.5, screen 0.0958333333 center top vertical maxrows 3 box Left reverse width 2 noenhanced
set label 1 '2 ms' at 0.120999752, 0.153014858 left font ',8' tc lt 1 front noenhanced
set label 2 '1 ms' at 0.130846175, 0.0735150757 left font ',8' tc lt 1 front noenhanced
set label 3 '0.5 ms' at 0.198450301, 0.0796508205 left font ',8' tc lt 1 front noenhanced
set label 4 '2 ms' at 1.68584105, 0.142883009 left font ',8' tc lt 2 front noenhanced
set label 5 '1 ms' at 2.95667382, 0.0508960563 left font ',8' tc lt 2 front noenhanced
set label 6 '0.5 ms' at 2.89563423, 0.0820287107 left font ',8' tc lt 2 front noenhanced
set label 7 '2 ms' at 0.220894419, 0.104683159 left font ',8' tc lt 3 front noenhanced
set label 8 '1 ms' at 0.281583804, 0.08770692 left font ',8' tc lt 3 front noenhanced
set label 9 '0.5 ms' at 0.435297074, 0.10422212 left font ',8' tc lt 3 front noenhanced
set label 10 '2 ms' at 2.9203943, 0.182194279 left font ',8' tc lt 4 front noenhanced
set label 11 '1 ms' at 4.31411126, 0.0564446394 left font ',8' tc lt 4 front noenhanced
set label 12 '0.5 ms' at 7.55997228, 0.065791607 left font ',8' tc lt 4 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'euler linear', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'euler pgs:20', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'rattle linear', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'rattle pgs:20'
