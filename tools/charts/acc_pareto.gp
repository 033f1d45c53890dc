# Error against cost per scene, every integrator over the step sweep; the Pareto front dashed.
reset
set datafile separator ","
f = dir."/sweep_double.csv"
set multiplot layout 2,3 title "Error against cost (double build). x: ns per body per simulated second (cost per step x steps per second); y: error relative to the scene's size.\nEach line is one integrator from 15 Hz (left) to 15360 Hz (right); circled: 60 Hz; black dashed: the Pareto front" font ",12"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set yrange [1e-15:10]
set grid
set xlabel "ns per body per simulated second" font ",10"
set key bottom left font ",10" samplen 2
do for [i=1:6] {
    sc = word(scenes, i)
    set title sc noenhanced
    if (i == 1) { set key } else { unset key }
    plot for [j=1:4] f using ((strcol(1) eq sc && strcol(2) eq word(igs, j) && $7 > 0 && $7 < 1e30) ? $12 : NaN):7 \
            with linespoints lc rgb word(cols, j) pt 7 ps 0.45 lw 1.5 title word(igl, j), \
         f using ((strcol(1) eq sc && $13 == 1) ? $12 : NaN):7 smooth unique with lines lc rgb "black" lw 2 dt 2 title "Pareto front", \
         f using ((strcol(1) eq sc && $4 == 60 && $7 > 0 && $7 < 1e30) ? $12 : NaN):7 with points pt 6 ps 1.6 lc rgb "black" title "60 Hz"
}
