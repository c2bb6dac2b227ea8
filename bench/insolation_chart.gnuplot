# Error of the binned insolation against the per-instant integral, over the azimuth sectors N and
# the elevation band, from demlight_insolation_bench's CSV (docs/accuracy.md#insolation-accuracy).
# Usage: gnuplot -e "csv='docs/bench/insolation_bins.csv'; dem='mount_st_helens_1980_usgs'; out='x.png'" \
#          bench/insolation_chart.gnuplot        (an out ending in .svg gives an SVG)
# One panel per day of the CSV: the global's mean absolute error relative to its mean (percent)
# against N, one line per band; the 1 % target dashed.
set datafile separator comma
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 1200,520 font "DejaVu Sans,12" } \
else { set terminal pngcairo size 1200,520 font "DejaVu Sans,12" }
set output out
days = system(sprintf("tail -n +2 %s | cut -d, -f1 | sort -u | tr '\\n' ' '", csv))
set multiplot layout 1, words(days) title sprintf("binned insolation against the per-instant integral (10-min steps) — %s", dem) noenhanced
set logscale x 2
set xtics (8, 16, 32, 64, 128)
set xrange [6:170]
set logscale y
set yrange [0.02:30]
set format y "%g"
set grid xtics ytics mytics lc rgb "#dddddd"
set xlabel "azimuth sectors N"
set ylabel "global MAE / mean (%)"
set key top right title "elevation band"
bands = "0.5 1 2 4 8"
do for [d in days] {
    set title d
    plot for [b in bands] sprintf("< awk -F, '$1 == \"%s\" && $3 == %s' %s | sort -t, -k2,2n", d, b, csv) \
             using 2:($6 * 100) with linespoints lw 2 pt 7 title sprintf("%s°", b), \
         1 with lines dt 2 lc rgb "black" title "1 % target"
}
unset multiplot
