# Scaling chart of the benchmark: ms per step against N (log-log) per scene, rigid and the
# peers measured in the same run, Box2D v3.2 as the issue quotes it (not measured here).
#   gnuplot -e "csv='build/charts/bench_scaling.csv'; out='build/charts/bench_scaling'" tools/bench.gp
# It plots the CSV's settling_mean_ms: the mean step time until the pile rests (every step when
# it never does).  The median of 600 steps, the issue's figure, is ~0 for an engine whose pile
# falls asleep early, which hides the growth rate the chart is for.  A series the run lacks
# (peers not installed, collision not built) is left out of the plot.
reset
scenes = "rain boxes free0"
titles = "'rain: circles r 0.5 into a container' 'boxes: unit squares into a container' 'free0: no shapes, gravity + drag'"
engines = "rigid box2d chipmunk"
labels = "'rigid' 'Box2D 2.4.1' 'Chipmunk 7.0.3'"
colors = "'#d62728' '#1f77b4' '#2ca02c'"
points = "7 5 9"
widths = "3 1.5 1.5"

# One file per scene and engine: N, median ms.
dir = out."_series"
system(sprintf("rm -rf '%s' && mkdir -p '%s' && awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == \"settling_mean_ms\") c = i; next } c && $c + 0 > 0 { print $2 \",\" $c > (\"%s/\" $1 \"_\" $3 \".csv\") }' '%s'", dir, dir, dir, csv))

# The issue's Box2D v3.2 figures (ms per step): quoted, not measured.
system(sprintf("printf 'rain,4000,1.20\\nrain,10000,8.2\\nboxes,4000,1.23\\nboxes,10000,6.0\\nfree0,100000,3.6\\n' > '%s/v3.csv'", dir))

set datafile separator ","
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1500,520 dynamic font "Helvetica,13" background "white"
    } else {
        set terminal pngcairo size 1500,520 font "Helvetica,11" background "white"
    }
    set output out.".".fmt
    set multiplot layout 1,3 title "ms per step against N while the scene is active (mean until the pile rests; dt = 1/60 s, one thread; log-log)" font ",14"
    set logscale xy
    set format x "10^{%T}"
    set format y "10^{%T}"
    set grid
    set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
    set xlabel "N (bodies)"
    set ylabel "ms per step"
    set key top left samplen 2
    do for [i=1:3] {
        sc = word(scenes, i)
        set title word(titles, i) noenhanced
        cmd = ""
        do for [j=1:3] {
            f = sprintf("%s/%s_%s.csv", dir, sc, word(engines, j))
            if (system(sprintf("test -s '%s' && echo 1 || echo 0", f)) eq "1") {
                cmd = cmd . sprintf("'%s' using 1:2 with linespoints lc rgb '%s' pt %s ps 0.8 lw %s title '%s', ", \
                                    f, word(colors, j), word(points, j), word(widths, j), word(labels, j))
            }
        }
        cmd = cmd . sprintf("'%s/v3.csv' using ((strcol(1) eq '%s') ? $2 : 1/0):3 with points pt 6 ps 1.8 lc rgb 'black' title 'Box2D v3.2 (quoted median)'", dir, sc)
        eval "plot " . cmd
    }
    unset multiplot
    set output
}
