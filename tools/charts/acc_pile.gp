# A pile of five boxes with mass ratio 1 and 100, started at rest: how far it sinks.
reset
set datafile separator ","
f = dir."/pile_double.csv"
set title "Five 1 m boxes started at rest on the ground (exact: nothing moves), 5 s, double build\nlargest |y - y_{rest}| against step rate (>= 0.5 m: boxes passed into each other)\nsolid: masses 1..100 kg bottom up, default solver iterations; dotted: the same with 64 iterations; dashed: all 1 kg" font ",12"
set xlabel "steps per second (Hz)"
set ylabel "largest |y - y_{rest}| over the run (m)"
set logscale xy
set format y "10^{%T}"
set xrange [25:280]
set xtics (30, 60, 120, 240)
set grid
set key outside right font ",10"
plot for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 100 && $4 == 0) ? $5 : NaN):6 with linespoints lw 2 pt 7 lc rgb word(cols, j) title word(igl, j)." ratio 100", \
     for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 100 && $4 == 64) ? $5 : NaN):6 with linespoints lw 1.5 dt 3 pt 4 lc rgb word(cols, j) title word(igl, j)." ratio 100, 64 it.", \
     for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 1) ? $5 : NaN):6 with linespoints lw 1.5 dt 2 pt 6 lc rgb word(cols, j) title word(igl, j)." ratio 1"
