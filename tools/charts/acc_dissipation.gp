# One step of friction and of quadratic drag from v = 1 m/s: naive explicit vs the library.
reset
set datafile separator ","
f = dir."/dissipation_double.csv"
set multiplot layout 1,2 title "One 60 Hz step from v = 1 m/s: the naive explicit update reverses the velocity, the library never does" font ",13"
set grid
set ylabel "velocity after the step (m/s)"
set yrange [-3.2:1.1]
set key bottom left
set title "surface friction, r = {/Symbol m} N dt / (m |v|)"
set xlabel "r"
plot f using ((strcol(1) eq "friction" && strcol(3) eq "naive") ? $2 : NaN):5 with lines lw 3 lc rgb "black" title "naive v - {/Symbol m}N/m dt sign(v)", \
     for [j=1:4] f using ((strcol(1) eq "friction" && strcol(3) eq word(igs, j)) ? $2 : NaN):5 with linespoints lw 1.5 pt j+4 ps 0.6 lc rgb word(cols, j) title word(igl, j), \
     0 with lines lc rgb "#888888" notitle
set title "quadratic drag, r = c |v| dt / m"
plot f using ((strcol(1) eq "drag" && strcol(3) eq "naive") ? $2 : NaN):5 with lines lw 3 lc rgb "black" title "naive v - c|v|v/m dt", \
     for [j=1:4] f using ((strcol(1) eq "drag" && strcol(3) eq word(igs, j)) ? $2 : NaN):5 with linespoints lw 1.5 pt j+4 ps 0.6 lc rgb word(cols, j) title word(igl, j), \
     1/(1 + x) with lines lw 1.5 dt 2 lc rgb "black" title "exact 1/(1 + r)", \
     0 with lines lc rgb "#888888" notitle
