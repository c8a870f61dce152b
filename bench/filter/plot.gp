# Plot of the filter-accuracy harness' velocity series (docs/img/filter.png).
# Regenerate (needs gnuplot-nox, not part of scripts/setup):
#   build/<dir>/bench/filter_accuracy --csv /tmp/filter.csv
#   gnuplot -e "csv='/tmp/filter.csv'; out='docs/img/filter.png'" bench/filter/plot.gp
if (!exists("csv")) csv = "filter.csv"
if (!exists("out")) out = "filter.png"
set terminal pngcairo size 1200,900 font "Sans,11"
set output out
set multiplot layout 2,1 title "Figure-eight, mean 2 m/s, 100 Hz, 0.5 mm noise, 2 % drops, 200 ms occlusion at 12.0 s, 10 cm outliers"
set grid
set key outside right top
set xlabel "capture time (s)"
set ylabel "north velocity v_N (m/s)"
set object 1 rect from 12.0, graph 0 to 12.2, graph 1 fc rgb "#eeeeee" behind
set yrange [-3:3]
set xrange [10.5:13.5]
plot csv index 0 using 2:3 with lines lw 3 lc rgb "black" title "truth", \
     csv index 2 using 2:3 with lines lw 1 lc rgb "#bbbbbb" title "finite differences", \
     csv index 3 using 2:3 with lines lw 1.5 lc rgb "#e69f00" title "FD + 30 Hz LPF", \
     csv index 4 using 2:3 with steps lw 2 lc rgb "#cc79a7" title "original (10 Hz KF)", \
     csv index 1 using 2:3 with lines lw 2 lc rgb "#0072b2" title "mocaplink Tracker"
set title "zoom: occlusion (grey) and recovery"
set xrange [11.7:12.6]
set yrange [-2.2:0.3]
replot
unset multiplot
