# Speed against accuracy chart for one DEM of demlight_tradeoff_bench's CSV.
# Usage: gnuplot -e "csv='docs/bench/tradeoff.csv'; dem='mount_st_helens_1980_usgs'; out='x.png'" \
#          bench/tradeoff_chart.gnuplot
# One panel per error metric: time per cell against error, log-log; every method / parameter set
# is a labelled point; rows the bench marked Pareto-optimal (column 7) are circled and joined.
# The scene plans of --quality ("quality auto", the default, and "quality full") are green
# diamonds with bold labels. A zero error (the reference itself) is drawn at the floor value.
floor = 1e-4
set datafile separator comma
set terminal pngcairo size 1800,1400 font "DejaVu Sans,11"
set output out
set multiplot layout 2,2 title sprintf("demlight speed vs accuracy — %s (1 thread; error 0 drawn at %g)", dem, floor) font ",15" noenhanced
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "time per cell (ns, whole grid / cells, median of repeats)"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key top right font ",10"
set offsets graph 0.05, graph 0.25, graph 0.1, graph 0.1
sel(m) = (strcol(3) eq dem && strcol(5) eq m)
err(m) = sel(m) ? ($6 > floor ? $6 : floor) : NaN
front(m) = (sel(m) && $7 == 1) ? ($6 > floor ? $6 : floor) : NaN
# the front rows of one metric, sorted by time, for the connecting line
frontrows(m) = sprintf("< awk -F, '$3 == \"%s\" && $5 == \"%s\" && $7 == 1' %s | sort -t, -k4,4g", dem, m, csv)
lab = 'strcol(1)." ".strcol(2)'
isplan = 'strcol(1) eq "quality auto" || strcol(1) eq "quality full"'
plan(m) = (@isplan) ? err(m) : NaN
autoplan(m) = strcol(1) eq "quality auto" ? err(m) : NaN
fullplan(m) = strcol(1) eq "quality full" ? err(m) : NaN
other(m) = (@isplan) ? NaN : err(m)
# labels jittered vertically by row so that points with equal errors stay readable
jit(m) = other(m) * 10**(0.07 * ((int($0) % 5) - 2))
do for [k = 1:4] {
  m = word("horizon_median_abs_deg sun_visibility_mae sun_irradiance_mae sky_K_mae", k)
  t = word("'sun horizon: median |error| (deg)' 'sun visibility: mean |error|' 'sun irradiance: mean |error|' 'sky K: mean |error|'", k)
  set title t font ",13"
  set ylabel t
  plot frontrows(m) using 4:($6 > floor ? $6 : floor) with lines lw 2 lc rgb "#d62728" title "Pareto front", \
       csv skip 1 using 4:(front(m)) with points pt 6 ps 3 lw 2 lc rgb "#d62728" notitle, \
       '' skip 1 using 4:(other(m)) with points pt 7 ps 1.2 lc rgb "#1f77b4" title "method / parameters", \
       '' skip 1 using 4:(jit(m)):(@lab) with labels left offset 0.8,0 font ",8" noenhanced notitle, \
       '' skip 1 using 4:(plan(m)) with points pt 13 ps 2.4 lc rgb "#2ca02c" title "--quality auto (default) / full", \
       '' skip 1 using 4:(autoplan(m)):(@lab) with labels right offset -1.2,0.8 font ",10:Bold" tc rgb "#1a7f1a" noenhanced notitle, \
       '' skip 1 using 4:(fullplan(m)):(@lab) with labels right offset -1.2,-0.8 font ",10:Bold" tc rgb "#1a7f1a" noenhanced notitle
}
unset multiplot
