# Tunnelling: the fraction of start phases in which a 10 cm ball passes a 1 cm wall at 60 Hz.
reset
set datafile separator ","
f = dir."/tunnel_double.csv"
set title "A 10 cm ball against a 1 cm wall at 60 Hz: share of 64 start phases that end past the wall (double build)\npoints measured, lines theory: naive 1 - (w + 2r)/(v dt), library discrete 1 - (w/2 + r)/(v dt), continuous 0" font ",12"
set xlabel "ball speed (m/s)"
set ylabel "share of runs that tunnel"
set logscale x
set xrange [1:1000]
set yrange [-0.05:1.05]
set grid
set key top left
ms = "lab_naive discrete continuous"
ml = "lab's naive discrete check|library, continuous off (discrete)|library, continuous collision (default)"
mc = "#d62728 #ff7f0e #2ca02c"
set arrow 1 from 300, graph 0 to 300, graph 1 nohead dt 3 lc rgb "#888888"
set label 1 "300 m/s" at 310, 0.5
plot for [j=1:3] f using ((strcol(1) eq word(ms, j)) ? $3 : NaN):5 with points pt 7 ps 0.9 lc rgb word(mc, j) title sprintf("%s", system(sprintf("echo '%s' | cut -d'|' -f%d", ml, j))), \
     for [j=1:3] f using ((strcol(1) eq word(ms, j)) ? $3 : NaN):6 with lines lw 1.5 lc rgb word(mc, j) notitle
