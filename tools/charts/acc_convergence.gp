# Error against step per scene: the slope is the measured order (least squares, in the key).
reset
set datafile separator ","
fd = dir."/sweep_double.csv"
ff = dir."/sweep_float.csv"
order(sc, ig, real) = system(sprintf("awk -F, '$1==\"%s\" && $2==\"%s\" {v=$5; if (v==\"nan\" || v==\"-nan\") v=\"n/a\"; else v=sprintf(\"%%.2f\", v); printf \"%%s\", v}' %s/orders_%s.csv", sc, ig, dir, real))
set multiplot layout 2,3 title "Measured convergence: error against step dt. Solid: double build, dashed: float build (it meets rounding near 10^{-6}).\nKey: measured order p in double / float (least squares where 0.05 > error > 10 eps steps); theory 1, 1, 2, 4" font ",12"
set logscale xy
set format x logfmt
set format y logfmt
set yrange [1e-16:1]
set xlabel "dt (s)"
set grid
set key bottom right font ",9" samplen 2
do for [i=1:6] {
    sc = word(scenes, i)
    set title sc noenhanced
    plot for [j=1:4] fd using ((strcol(1) eq sc && strcol(2) eq word(igs, j) && $7 > 0 && $7 < 1e30) ? $5 : NaN):7 \
            with linespoints lc rgb word(cols, j) pt 7 ps 0.4 lw 1.5 \
            title sprintf("%s p = %s / %s", word(igl, j), order(sc, word(igs, j), "double"), order(sc, word(igs, j), "float")), \
         for [j=1:4] ff using ((strcol(1) eq sc && strcol(2) eq word(igs, j) && $7 > 0 && $7 < 1e30) ? $5 : NaN):7 \
            with lines lc rgb word(cols, j) dt 2 lw 1 notitle
}
