# accuracy.gp: renders the accuracy lab's CSV (tools/accuracy in the float and the double
# build) into SVG and PNG.  Run by `make charts`:  gnuplot -e "dir='build/charts'" tools/charts/accuracy.gp
# With check='DIR' it draws nothing and writes each chart's plotted points to DIR/NAME.table
# instead (gnuplot's table mode), for tests/pictures/check_charts.py to hold against the CSV.
if (!exists("dir")) dir = "build/charts"
if (!exists("src")) src = "tools/charts"
# Tick labels; in check mode full numbers, since gnuplot writes table points in them.
logfmt = exists("check") ? "%.10g" : "10^{%T}"
linfmt = exists("check") ? "%.10g" : "%g"
charts = "pareto energy60 convergence stability framerate dissipation"
# the collision scenes, when the lab was built with collision
if (system(sprintf("test -f '%s/tunnel_double.csv' && echo yes", dir)) eq "yes") charts = charts." tunnel pile"
igs = "explicit_euler semi_implicit_euler verlet rk4"
igl = "explicit\\_Euler semi-implicit\\_Euler Verlet RK4"
cols = "#d62728 #1f77b4 #2ca02c #9467bd"
scenes = "oscillator damped_oscillator projectile_linear_drag fall_quadratic_drag throw_up_quadratic_drag slide_friction"
do for [c in charts] {
    if (exists("check")) {
        check_table = sprintf("%s/%s.table", check, c)
        set table check_table
        load sprintf("%s/acc_%s.gp", src, c)
        unset multiplot
        unset table
        continue
    }
    do for [fmt in "svg png"] {
        if (fmt eq "svg") {
            set terminal svg size 1200,780 dynamic enhanced font "Helvetica,12" background rgb "white"
        } else {
            set terminal pngcairo size 1200,780 enhanced font "Helvetica,11" background rgb "white"
        }
        set output sprintf("%s/%s.%s", dir, c, fmt)
        load sprintf("%s/acc_%s.gp", src, c)
        unset multiplot
        set output
    }
}
