# Error against cost per scene, every integrator over the step sweep; the Pareto front dashed.
# The front is the CSV's pareto = 1 rows of the scene, gathered into one table first and
# sorted by cost (smooth unique), then drawn as steps: at any cost, the best error reachable
# for that cost or less.  (Drawn straight from the CSV, a line would join only the front
# points of one integrator that sit next to each other in the file.)
reset
set datafile separator ","
f = dir."/sweep_double.csv"
set multiplot layout 2,3 title "Error against cost (double build). x: ns per body per simulated second (cost per step x steps per second); y: error relative to the scene's size.\nEach line is one integrator from 15 Hz (left) to 15360 Hz (right); circled: 60 Hz; black dashed steps: the Pareto front (the best error for that cost or less)" font ",12"
set logscale xy
set format x logfmt
set format y logfmt
set yrange [1e-15:1e3]
set grid
set xlabel "ns per body per simulated second" font ",10"
set key bottom left font ",10" samplen 2
do for [i=1:6] {
    sc = word(scenes, i)
    set title sc noenhanced
    if (i == 1) { set key } else { unset key }
    set table $front separator comma
    plot f using 12:7 with table if (strcol(1) eq sc && int(strcol(13)) == 1)
    unset table
    if (exists("check_table")) { set table check_table append }
    plot for [j=1:4] f using ((strcol(1) eq sc && strcol(2) eq word(igs, j) && $7 > 0 && $7 < 1e30) ? $12 : NaN):7 \
            with linespoints lc rgb word(cols, j) pt 7 ps 0.45 lw 1.5 title word(igl, j), \
         $front using 1:2 smooth unique with steps lc rgb "black" lw 2 dt 2 title "Pareto front", \
         f using ((strcol(1) eq sc && $4 == 60 && $7 > 0 && $7 < 1e30) ? $12 : NaN):7 with points pt 6 ps 1.6 lc rgb "black" title "60 Hz"
}
