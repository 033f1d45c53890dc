# Energy of the undamped 1 Hz spring at 60 Hz over 10 s, per integrator.
reset
set datafile separator ","
f = dir."/energy60_double.csv"
set multiplot layout 1,2 title "Energy of a 1 Hz spring (1 kg, k = 4{/Symbol p}^2 N/m) stepped at 60 Hz, double build" font ",13"
set xlabel "t (s)"
set ylabel "E / E_0"
set logscale y
set format y logfmt
set grid
set key top left
set title "all four (log scale): explicit Euler gains (1 + ({/Symbol w}dt)^2) per step"
plot for [j=1:4] f using ((strcol(1) eq "oscillator" && strcol(2) eq word(igs, j)) ? $3 : NaN):4 with lines lw 2 lc rgb word(cols, j) title word(igl, j)
unset logscale y
set format y linfmt
set ylabel "E / E_0 - 1"
set title "the three that hold it (linear scale)"
set key bottom left
set label 1 "RK4 loses 1.1 x 10^{-5} in 10 s (|R(i{/Symbol w}dt)|^2 = 1 - ({/Symbol w}dt)^6/72 + ...)" at graph 0.03, graph 0.93 font ",10"
plot for [j=2:4] f using ((strcol(1) eq "oscillator" && strcol(2) eq word(igs, j)) ? $3 : NaN):($4 - 1) with lines lw 1.5 lc rgb word(cols, j) title word(igl, j)
