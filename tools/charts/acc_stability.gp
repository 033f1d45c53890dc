# Stability: amplitude factor per step against omega*dt, and the boundary found by bisection.
reset
set datafile separator ","
g = dir."/growth_double.csv"
sd = dir."/stability_double.csv"
sf = dir."/stability_float.csv"
set multiplot layout 1,2 title "Stability on the undamped oscillator (a stiff spring): where each integrator fails" font ",13"
set title "amplitude factor per step: points measured (400 steps), lines theory"
set xlabel "{/Symbol w} dt"
set ylabel "|{/Symbol l}| per step"
set logscale y
set yrange [0.3:30]
set xrange [0:4]
set grid
set key top left
set arrow 1 from 2, graph 0 to 2, graph 1 nohead dt 3 lc rgb "#1f77b4"
set arrow 2 from 2*sqrt(2), graph 0 to 2*sqrt(2), graph 1 nohead dt 3 lc rgb "#9467bd"
set label 1 "2" at 2.03, 0.4 tc rgb "#1f77b4"
set label 2 "2{/Symbol \326}2" at 2*sqrt(2)+0.03, 0.4 tc rgb "#9467bd"
plot for [j=1:4] g using ((strcol(1) eq word(igs, j)) ? $3 : NaN):4 with points pt 7 ps 0.5 lc rgb word(cols, j) title word(igl, j), \
     for [j=1:4] g using ((strcol(1) eq word(igs, j)) ? $3 : NaN):5 with lines lw 1 lc rgb word(cols, j) notitle
unset arrow
unset label
unset logscale y
set title "largest stable {/Symbol w} dt by bisection (E/E_0 <= 10^4 over 2000 steps)"
set xlabel ""
set ylabel "{/Symbol w} dt"
set yrange [0:3.3]
set xrange [*:*]
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set key top left
set bmargin 4
set xtics ("explicit\nEuler*" 0, "semi-implicit\nEuler" 1, "Verlet" 2, "RK4" 3)
set label 3 "* no stable step: the bisection finds\n  sqrt(10^{4/2000} - 1) = 0.068, and 0 as the horizon grows" at graph 0.03, graph 0.72 font ",10"
plot sd every ::1 using 3 title "measured, double" lc rgb "#444444", \
     sf every ::1 using 3 title "measured, float" lc rgb "#999999", \
     sd every ::1 using 4 title "theory" lc rgb "#ffbb55"
