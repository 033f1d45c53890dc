# bench_pareto.gp: quality against cost from `bench --sweep` (tools/bench_sweep.c), every
# engine on one chart: a row per scene (boxes, rain), a column per measure (sleeping off,
# against the median ms per step: the deepest overlap at the end, the deepest over the run,
# the mean overlap at the end; sleeping on, against the mean ms per step: the time to rest).  Each line is one engine's
# solver setting swept (the CSV's curve); circled: each engine's default; black dashed
# steps: the Pareto front over every engine (the CSV's front_* = 1 rows, sorted by cost).
#   gnuplot -e "csv='build/charts/bench_pareto.csv'; out='build/charts/bench_pareto'" tools/charts/bench_pareto.gp
reset
set datafile separator ","
array curves[6] = ["rigid: velocity iterations (3 position)", "rigid: position iterations (8 velocity)", \
                   "Box2D v3: substeps", "Box2D 2.4: velocity iterations (3 position)", \
                   "Box2D 2.4: position iterations (8 velocity)", "Chipmunk 7: iterations"]
array colors[6] = ["#d62728", "#ff7f0e", "#1f77b4", "#2ca02c", "#98df8a", "#9467bd"]
array points[6] = [7, 5, 9, 11, 13, 15]
array widths[6] = [2.5, 2.5, 1.5, 1.5, 1.5, 1.5]
scenes = "boxes rain"
# per column: the cost column, the measure's column, its front flag, its scale to the axis
M = 4
array cost_col[M] = [8, 8, 8, 12]
array q_col[M] = [9, 10, 11, 14]
array front_col[M] = [15, 16, 17, 18]
array q_scale[M] = [1000.0, 1000.0, 1000.0, 1.0]
array q_label[M] = ["deepest overlap at the end (mm)", "deepest overlap over the run (mm)", \
                    "mean overlap at the end (mm)", "time to rest (s)"]
array x_label[M] = ["ms per step (median, sleeping off)", "ms per step (median, sleeping off)", \
                    "ms per step (median, sleeping off)", "ms per step (mean over the run, sleeping on)"]
array q_title[M] = ["deepest overlap at the end", "deepest overlap during the run (every 10 steps)", \
                    "mean overlap at the end", "time to rest, sleeping on"]
floor_mm = 1e-3   # overlaps below a micrometre are drawn on the axis floor
never = system(sprintf("awk -F, 'NR > 1 && $13 < 0 { print $14; exit }' '%s'", csv)) + 0

do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1900,900 dynamic enhanced font "Helvetica,12" background rgb "white"
    } else {
        set terminal pngcairo size 1900,900 enhanced font "Helvetica,11" background rgb "white"
    }
    set output out.".".fmt
    set multiplot layout 2,M title "Quality against cost: every engine at several solver settings (dt = 1/60 s, one thread; bench --sweep).\nLines: one setting swept per engine; circled: each engine's default; black dashed steps: the Pareto front over all engines (the best for that cost or less)" font ",13"
    set grid
    set logscale x
    set format x "%g"
    set key bottom right font ",9" samplen 2 opaque
    do for [s=1:2] {
        sc = word(scenes, s)
        n = system(sprintf("awk -F, 'NR > 1 && $1 == \"%s\" { print $2; exit }' '%s'", sc, csv))
        do for [m=1:M] {
            set title sprintf("%s %s: %s", sc, n, q_title[m]) noenhanced
            set xlabel x_label[m] font ",10"
            set ylabel q_label[m] font ",10"
            if (m < M) {
                set logscale y
                set format y "10^{%T}"
                set yrange [floor_mm:*]
            } else {
                unset logscale y
                set format y "%g"
                if (never > 0) { set yrange [0:never * 1.08] } else { set yrange [0:*] }
            }
            if (s == 1 && m == 1) { set key } else { unset key }
            set table $front separator comma
            plot csv using (column(cost_col[m])):(column(q_col[m]) * q_scale[m]) with table \
                 if (strcol(1) eq sc && int(column(front_col[m])) == 1)
            unset table
            unset label 1
            if (m == M && never > 0) {
                set label 1 sprintf("never at rest in %g s", never) at graph 0.02, first never * 1.035 font ",9"
            }
            plot for [i=1:6] csv using ((strcol(1) eq sc && strcol(4) eq curves[i]) ? column(cost_col[m]) : NaN):\
                     (column(q_col[m]) * q_scale[m] > floor_mm ? column(q_col[m]) * q_scale[m] : floor_mm) \
                     with linespoints lc rgb colors[i] pt points[i] ps 0.7 lw widths[i] title curves[i] noenhanced, \
                 $front using 1:($2 > floor_mm ? $2 : floor_mm) smooth unique with steps lc rgb "black" lw 1.5 dt 2 \
                     title "Pareto front", \
                 csv using ((strcol(1) eq sc && int(column(7)) == 1) ? column(cost_col[m]) : NaN):\
                     (column(q_col[m]) * q_scale[m] > floor_mm ? column(q_col[m]) * q_scale[m] : floor_mm) \
                     with points pt 6 ps 2.2 lc rgb "black" title "default setting"
        }
    }
    unset multiplot
    set output
}
