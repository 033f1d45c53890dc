# Tunnelling: the fraction of start phases in which a 10 cm ball passes a 1 cm wall at 60 Hz.
reset
set datafile separator ","
f = dir."/tunnel_double.csv"
set title "A 10 cm ball against a 1 cm wall at 60 Hz: share of 64 start phases that end past the wall (double build)\npoints measured; lines theory: naive check 1 - (w + 2r)/(v dt); the library's discrete check lies between that and\n1 - (w/2 + r)/(v dt) (it catches at most every overlapping sample, always one in the near half); continuous: 0" font ",12"
set xlabel "ball speed (m/s)"
set ylabel "share of runs that tunnel"
set logscale x
set xrange [1:1000]
set yrange [-0.05:1.05]
set grid
set key top left
set arrow 1 from 300, graph 0 to 300, graph 1 nohead dt 3 lc rgb "#888888"
set label 1 "300 m/s" at 310, 0.5
sel(m) = strcol(1) eq m ? $3 : NaN
plot f using (sel("lab_naive")):5 with points pt 7 ps 0.9 lc rgb "#d62728" title "lab's naive discrete check", \
     f using (sel("lab_naive")):6 with lines lw 1.5 lc rgb "#d62728" notitle, \
     f using (sel("discrete")):5 with points pt 5 ps 0.8 lc rgb "#ff7f0e" title "library, continuous off (discrete)", \
     f using (sel("discrete")):6 with lines lw 1.5 lc rgb "#ff7f0e" notitle, \
     f using (sel("continuous")):5 with points pt 9 ps 1.0 lc rgb "#2ca02c" title "library, continuous collision (default)", \
     f using (sel("continuous")):6 with lines lw 1.5 lc rgb "#2ca02c" notitle
