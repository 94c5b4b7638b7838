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
set title 'falling doll: speed against accuracy (reference rattle linear at dt 6.25e-05 s, 1 s simulated, 20 sample times)' . "\n" . '(chaotic: error does not rank the methods; no method''s error falls as dt is refined)' noenhanced
set lmargin at screen 0.085
set rmargin at screen 0.975
set tmargin at screen 0.92
set bmargin at screen 0.168055556
set logscale xy
set xrange [0.01:1]
set yrange [0.1:1]
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
set label 1 '2 ms' at 0.0141297317, 0.581073882 left font ',8' tc lt 1 front noenhanced
set label 2 '1 ms' at 0.0201548184, 0.713800825 left font ',8' tc lt 1 front noenhanced
set label 3 '0.5 ms' at 0.0343059589, 0.622800507 left font ',8' tc lt 1 front noenhanced
set label 4 '0.25 ms' at 0.0747076249, 0.583772023 left font ',8' tc lt 1 front noenhanced
set label 5 '2 ms' at 0.127216941, 0.562841343 left font ',8' tc lt 2 front noenhanced
set label 6 '1 ms' at 0.1587147, 0.731842789 left font ',8' tc lt 2 front noenhanced
set label 7 '0.5 ms' at 0.219234738, 0.412554684 left font ',8' tc lt 2 front noenhanced
set label 8 '0.25 ms' at 0.26245184, 0.567651471 left font ',8' tc lt 2 front noenhanced
set label 9 '2 ms' at 0.0178900452, 0.665444713 left font ',8' tc lt 3 front noenhanced
set label 10 '1 ms' at 0.0370702732, 0.829641019 left font ',8' tc lt 3 front noenhanced
set label 11 '0.5 ms' at 0.0527587925, 0.494805057 left font ',8' tc lt 3 front noenhanced
set label 12 '0.25 ms' at 0.104310059, 0.464742296 left font ',8' tc lt 3 front noenhanced
set label 13 '2 ms' at 0.192934019, 0.621430078 left font ',8' tc lt 4 front noenhanced
set label 14 '1 ms' at 0.213210632, 0.78827827 left font ',8' tc lt 4 front noenhanced
set label 15 '0.5 ms' at 0.42464327, 0.538920707 left font ',8' tc lt 4 front noenhanced
set label 16 '0.25 ms' at 0.754782951, 0.523843125 left font ',8' tc lt 4 front noenhanced
plot data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no other cell both cheaper and more accurate)', \
     data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle, \
     data index 1 using 1:2 with linespoints lt 1 lw 2 pt 7 ps 1.2 title 'euler linear', \
     data index 2 using 1:2 with linespoints lt 2 lw 2 pt 7 ps 1.2 title 'euler pgs:20', \
     data index 3 using 1:2 with linespoints lt 3 lw 2 pt 7 ps 1.2 title 'rattle linear', \
     data index 4 using 1:2 with linespoints lt 4 lw 2 pt 7 ps 1.2 title 'rattle pgs:20'
