# A jump's apex height against display frame rate: naive per-frame steps vs the accumulator.
reset
set datafile separator ","
f = dir."/framerate_double.csv"
set title "Apex of a 5 m/s jump (exact 1.2742 m) against display frame rate, double build\nsolid: one step per frame, dt = frame time; dashed: rg\\_world\\_advance at a fixed 1/60 s,\nbit-identical for every frame pattern; diamonds: jittered frames 1/144..1/30 s" font ",12"
set xlabel "display frame rate (Hz); jittered runs at their mean rate"
set ylabel "apex height (m)"
set grid
set key bottom right font ",10"
set xrange [25:250]
plot for [j=1:3] f using ((strcol(1) eq "steady" && strcol(3) eq word(igs, j)) ? $2 : NaN):5 with linespoints lw 2 pt 7 lc rgb word(cols, j) title word(igl, j)." per frame", \
     for [j=1:3] f using ((strcol(1) eq "steady" && strcol(3) eq word(igs, j)) ? $2 : NaN):6 with lines lw 2 dt 2 lc rgb word(cols, j) title word(igl, j)." accumulated", \
     for [j=1:3] f using ((strcol(1) eq "jitter" && strcol(3) eq word(igs, j)) ? $2 : NaN):5 with points pt 13 ps 1.5 lc rgb word(cols, j) notitle, \
     f using ((strcol(1) eq "steady" && strcol(3) eq "rk4") ? $2 : NaN):8 with lines lw 1 lc rgb "black" title "exact v_0^2/(2g)"
