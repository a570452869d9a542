# Map of an unround race (model.md §11.10): per cell the design figure, log10 of the best
# stable state's residual whirl |q| [m] (left; white: no stable state), and the number of
# stable equilibria (right); cells of the first-order regime Lambda <= 0.1 (§11.6) carry
# a small white dot. Reads summary_X_Y.csv of `stability-scan map`; re-run by hand with
#   gnuplot -e "csv='out/summary_omega_unroundness.csv'; png='m.png'; xname='omega'; yname='unroundness'; xunit='rad/s'; yunit='-'; logx='0'; logy='0'; title='x'" plots/unround_map.gp
if (!exists("csv")) csv = 'out/summary_omega_unroundness.csv'
if (!exists("png")) png = 'unround_map.png'
if (!exists("xname")) xname = 'omega'
if (!exists("yname")) yname = 'unroundness'
if (!exists("xunit")) xunit = 'rad/s'
if (!exists("yunit")) yunit = '-'
if (!exists("logx")) logx = '0'
if (!exists("logy")) logy = '0'
if (!exists("title")) title = 'unround race map'
if (!exists("subtitle")) subtitle = ''
# A flexible shaft's map (model.md §18.18) has no first-order regime column.
if (!exists("first_order")) first_order = '1'
# What the right panel counts, and what the left one's |q| is (a periodic orbit's largest |q|
# over its period on an anisotropic support, model.md §20.7).
if (!exists("states")) states = 'stable equilibria'
if (!exists("qlabel")) qlabel = 'log_{10} |q| of the best stable state [m]'

set terminal pngcairo size 1300,600 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
label(name, unit, lg) = (lg eq '1' ? 'log_{10} ' : '') . name . (unit eq '-' ? '' : ' [' . unit . ']')
# Image cells need an even grid: a log axis is drawn in log10 of its values.
X(v) = (logx eq '1' ? log10(v) : v)
Y(v) = (logy eq '1' ? log10(v) : v)
set xlabel label(xname, xunit, logx) noenhanced
set ylabel label(yname, yunit, logy) noenhanced
set multiplot layout 1,2 title heading noenhanced font ',9'
set palette defined (0 '#0b3d91', 0.5 '#f2c14e', 1 '#b2182b')
set cblabel qlabel
positive(q) = (q > 0 ? log10(q) : NaN)
# 4 decades below the largest |q|: a balanced state at zero unroundness (|q| = 0 up to
# rounding, ~1e-22 m) is drawn in the lowest colour.
stats csv using (positive(column("best_q_abs"))) nooutput
top = STATS_max
set cbrange [top - 4 : top]
set autoscale xfix
set autoscale yfix
set key below
dots = first_order eq '1' ? ", csv using (X(column(xname))):(column('first_order') > 0 ? Y(column(yname)) : NaN) with points pt 7 ps 0.3 lc rgb 'white' title 'first order (Lambda <= 0.1)'" : ""
plot csv using (X(column(xname))):(Y(column(yname))):(positive(column("best_q_abs"))) with image notitle @dots
# From 0, so that white is "none stable" and not the map's least count.
set cbrange [0:*]
set cblabel states
set palette defined (0 '#f7f7f7', 1 '#92c5de', 2 '#2166ac', 4 '#053061')
plot csv using (X(column(xname))):(Y(column(yname))):(column("stable")) with image notitle
unset multiplot
