# Scaling chart of the benchmark: ms per step against N (log-log) per scene, every engine
# measured in the same run with sleeping off (the bench's main figure: the median of the
# steps), one worker and all workers where the engine has threads.
#   gnuplot -e "csv='build/charts/bench_scaling.csv'; out='build/charts/bench_scaling'" tools/bench.gp
# The series are the CSV's engines (its entrants: rigid, rigid-2w, b2v3-avx2 ...), the floor
# loop left out; a series the run lacks (v3 or the peers not built) is not drawn.
reset
scenes = "rain boxes free0"
titles = "'rain: circles r 0.5 into a container' 'boxes: unit squares into a container' 'free0: no shapes, gravity + drag'"
# colour, point and width by engine, in this order (any other engine after them, grey); a
# threaded run (-Nw) is dashed in its engine's colour
known = "rigid b2v3-avx2 b2v3-sse2 box2d chipmunk"
labels = "'rigid' 'Box2D v3.2 AVX2' 'Box2D v3.2 SSE2' 'Box2D 2.4' 'Chipmunk 7'"
colors = "'#d62728' '#1f77b4' '#17becf' '#2ca02c' '#9467bd'"
points = "7 5 4 9 11"
widths = "3 1.5 1.5 1.5 1.5"

# One file per scene and entrant: N, median ms (sleeping off).
dir = out."_series"
system(sprintf("rm -rf '%s' && mkdir -p '%s' && awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == \"median_ms\") c = i; if ($i == \"sleep\") z = i }; next } c && z && $z == 0 && $3 != \"floor\" && $c + 0 > 0 { print $2 \",\" $c > (\"%s/\" $1 \"@\" $3 \".csv\") }' '%s'", dir, dir, dir, csv))
entrants = system(sprintf("ls '%s' | sed 's/^[^@]*@//; s/[.]csv$//' | sort -u | tr '\\n' ' '", dir))

set datafile separator ","
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1500,520 dynamic font "Helvetica,13" background "white"
    } else {
        set terminal pngcairo size 1500,520 font "Helvetica,11" background "white"
    }
    set output out.".".fmt
    set multiplot layout 1,3 title "ms per step against N, sleeping off for every engine (median of 600 steps; dt = 1/60 s; -Nw: N worker threads, dashed; log-log)" font ",14"
    set logscale xy
    set format x "10^{%T}"
    set format y "10^{%T}"
    set grid
    set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
    set xlabel "N (bodies)"
    set ylabel "ms per step"
    set key top left samplen 3 font ",10"
    do for [i=1:3] {
        sc = word(scenes, i)
        set title word(titles, i) noenhanced
        cmd = ""
        do for [j=0:words(known)] {
          do for [e in entrants] {
            f = sprintf("%s/%s@%s.csv", dir, sc, e)
            base = system(sprintf("echo '%s' | sed 's/-[0-9]*w$//'", e))
            k = 0
            do for [jj=1:words(known)] { if (word(known, jj) eq base) { k = jj } }
            if (k == j && system(sprintf("test -s '%s' && echo 1 || echo 0", f)) eq "1") {
                threads = base ne e
                col = k > 0 ? word(colors, k) : "#7f7f7f"
                pt = k > 0 ? word(points, k) : "1"
                lw = k > 0 ? word(widths, k) : "1.5"
                name = (k > 0 ? word(labels, k) : base) . (threads ? sprintf(", %s workers", system(sprintf("echo '%s' | sed 's/.*-\\([0-9]*\\)w$/\\1/'", e))) : "")
                cmd = cmd . sprintf("'%s' using 1:2 with linespoints lc rgb '%s' pt %s ps 0.8 lw %s dt %d title '%s', ", \
                                    f, col, pt, lw, threads ? 2 : 1, name)
            }
          }
        }
        if (strlen(cmd) > 0) { eval "plot " . cmd[1:strlen(cmd) - 2] }
    }
    unset multiplot
    set output
}
