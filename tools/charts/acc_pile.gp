# A pile of five boxes with mass ratio 1 and 100, started at rest: how far it sinks.
# A sink of exactly 0 (semi-implicit Euler at most rates) has no place on a log axis: it is
# drawn on the dashed floor line at 10^-16 and the line says so.  Each integrator's points
# sit 2.5% apart in x (explicit Euler left, RK4 right), so series that coincide (Verlet and
# RK4) show side by side instead of one hiding the other.
reset
set datafile separator ","
f = dir."/pile_double.csv"
floor = 1e-16
dodge(j) = 1 + 0.025 * (j - 2.5)
sink(e) = e > 0 ? e : floor
set title "Five 1 m boxes started at rest on the ground (exact: nothing moves), 5 s, double build\nlargest |y - y_{rest}| against step rate (>= 0.5 m: boxes passed into each other); integrators side by side at each rate\nsolid: masses 1..100 kg bottom up, default solver iterations; dotted: the same with 64 iterations; dashed: all 1 kg" font ",12"
set xlabel "steps per second (Hz)"
set ylabel "largest |y - y_{rest}| over the run (m)"
set logscale xy
set format y logfmt
set xrange [25:280]
set yrange [3e-17:1]
set xtics (30, 60, 120, 240)
set grid
set key outside right font ",10"
set arrow 1 from graph 0, first floor to graph 1, first floor nohead dt 2 lc rgb "#888888"
set label 1 "exactly 0 (no sink at all) is drawn on this line" at graph 0.02, first floor * 3 font ",10" tc rgb "#555555"
plot for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 100 && $4 == 0) ? $5 * dodge(j) : NaN):(sink($6)) with linespoints lw 2 pt 7 lc rgb word(cols, j) title word(igl, j)." ratio 100", \
     for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 100 && $4 == 64) ? $5 * dodge(j) : NaN):(sink($6)) with linespoints lw 1.5 dt 3 pt 4 lc rgb word(cols, j) title word(igl, j)." ratio 100, 64 it.", \
     for [j=1:4] f using ((strcol(1) eq word(igs, j) && $3 == 1 && $4 == 0) ? $5 * dodge(j) : NaN):(sink($6)) with linespoints lw 1.5 dt 2 pt 6 lc rgb word(cols, j) title word(igl, j)." ratio 1"
