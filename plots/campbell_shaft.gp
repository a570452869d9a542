# Campbell diagram of a flexible shaft (docs/model.md §16.1, §18; docs/guide.md §15):
# the signed fixed-frame whirl frequency of each rightmost eigenvalue against the speed
# (forward > 0, backward < 0), with the 1X line; below, the real part of the eigenvalues
# (growth rate: > 0 is unstable). Reads campbell_shaft_omega.csv of
# `stability-scan sweep SHAFT_SCENE --param omega`; by hand:
#   gnuplot -e "csv='out/campbell_shaft_omega.csv'; png='c.png'; unit='rad/s'; scale='1'; title='x'" plots/campbell_shaft.gp
# Columns by header name: omega, whirl, direction, re.
if (!exists("csv")) csv = 'out/campbell_shaft_omega.csv'
if (!exists("png")) png = 'campbell_shaft.png'
if (!exists("unit")) unit = 'rad/s'
if (!exists("scale")) scale = '1'
if (!exists("title")) title = 'Campbell diagram of the flexible shaft'
s = scale + 0

set terminal pngcairo size 1100,1000 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

fw(y) = strcol("direction") eq 'forward' ? y : NaN
bw(y) = strcol("direction") eq 'backward' ? y : NaN

set style line 1 lc rgb '#d62728' pt 7 ps 0.6   # forward whirl
set style line 2 lc rgb '#1f77b4' pt 6 ps 0.8   # backward whirl

stats csv using (column("omega") * s) nooutput
xmax = STATS_max
set xrange [0:xmax * 1.02]
set xlabel sprintf('speed {/Symbol w} [%s]', unit)
set grid
set key outside right top
set lmargin at screen 0.10
set rmargin at screen 0.72
set multiplot layout 2,1 title title noenhanced

set ylabel sprintf('whirl frequency {/Symbol W} [%s], fixed frame', unit)
set arrow 3 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  x with lines lc rgb 'black' lw 1 title '1X ({/Symbol W} = {/Symbol w})', \
  csv using (column("omega") * s):(fw(column("whirl") * s)) with points ls 1 title 'forward whirl ({/Symbol W} > 0)', \
  csv using (column("omega") * s):(bw(column("whirl") * s)) with points ls 2 title 'backward whirl ({/Symbol W} < 0)'
unset arrow 3

set ylabel 'Re {/Symbol l} [1/s] (growth rate; < 0 decays)'
set arrow 2 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  csv using (column("omega") * s):(fw(column("re"))) with points ls 1 title 'forward whirl', \
  csv using (column("omega") * s):(bw(column("re"))) with points ls 2 title 'backward whirl'
unset multiplot
