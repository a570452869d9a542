# Sweep chart: |q| and the spectral abscissa against the swept parameter, one colour
# per equilibrium family (both members of a family share it), stable solid, unstable
# dashed. Reads the CSV written by `stability-scan sweep`; re-run by hand with
#   gnuplot -e "csv='out/sweep_omega.csv'; png='sweep.png'; param='omega'; unit='rad/s'; logx='0'; title='x'" plots/sweep.gp
# Columns are read by their header names: step, the parameter's symbol, family, member, q_abs [m],
# spectral_abscissa [1/s], stable.
if (!exists("csv")) csv = 'out/sweep_omega.csv'
if (!exists("png")) png = 'sweep.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = 'sweep'

set terminal pngcairo size 1100,900 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

# A series is one (family, member); it is drawn only where its stability matches `st`.
# The line breaks where the series is absent at some values (the step index jumps).
series(fam, mem, st, y) = (strcol("family") eq fam && column("member") == mem) ? \
    (gap = (last >= 0 && column("step") != last + 1), last = column("step"), \
     (column("stable") == st && !gap) ? y : NaN) : NaN

# Signed log for the abscissa, which spans -10 .. +1e-7 1/s and whose sign is the point:
# S(a) = sgn(a) log10(1 + |a| / a0), with a0 = 1e-12 1/s.
a0 = 1e-12
S(a) = sgn(a) * log10(1 + abs(a) / a0)

colour_balanced = '#1f77b4'
colour_together = '#d62728'
colour_opposite = '#2ca02c'
set style line 1 lc rgb colour_balanced lw 2.5 dt 1
set style line 2 lc rgb colour_balanced lw 1.5 dt (6,4)
set style line 3 lc rgb colour_together lw 2.5 dt 1
set style line 4 lc rgb colour_together lw 1.5 dt (6,4)
set style line 5 lc rgb colour_opposite lw 2.5 dt 1
set style line 6 lc rgb colour_opposite lw 1.5 dt (6,4)

if (logx eq '1') set logscale x
set xlabel sprintf('%s [%s]', param, unit)
set grid
set key outside right top
set lmargin at screen 0.09
set rmargin at screen 0.72
set multiplot layout 2,1 title title noenhanced

set logscale y
set ylabel '|q| [m] (rotor excursion, rotating frame)'
set format y '10^{%T}'
plot \
  last = -1, csv using (column(param)):(series('together', 1, 1, column("q_abs"))) with lines ls 3 title 'together, stable', \
  last = -1, csv using (column(param)):(series('together', 1, 0, column("q_abs"))) with lines ls 4 title 'together, unstable', \
  last = -1, csv using (column(param)):(series('together', 2, 1, column("q_abs"))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 0, column("q_abs"))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 1, column("q_abs"))) with lines ls 5 title 'opposite, stable', \
  last = -1, csv using (column(param)):(series('opposite', 1, 0, column("q_abs"))) with lines ls 6 title 'opposite, unstable', \
  last = -1, csv using (column(param)):(series('opposite', 2, 1, column("q_abs"))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 0, column("q_abs"))) with lines ls 6 notitle, \
  NaN with lines ls 1 title 'balanced: q = 0 (off this log axis)'

unset logscale y
set format y '%g'
set ylabel 'spectral abscissa  sgn(a) log_{10}(1 + |a| / 10^{-12} s^{-1})'
set ytics ('0' 0)
do for [e = -10:2:2] {
  set ytics add (sprintf('10^{%d}', e) S(10.0**e), sprintf('-10^{%d}', e) S(-(10.0**e)))
}
set arrow from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  last = -1, csv using (column(param)):(series('balanced', 1, 1, S(column("spectral_abscissa")))) with lines ls 1 title 'balanced, stable', \
  last = -1, csv using (column(param)):(series('balanced', 1, 0, S(column("spectral_abscissa")))) with lines ls 2 title 'balanced, unstable', \
  last = -1, csv using (column(param)):(series('balanced', 2, 1, S(column("spectral_abscissa")))) with lines ls 1 notitle, \
  last = -1, csv using (column(param)):(series('balanced', 2, 0, S(column("spectral_abscissa")))) with lines ls 2 notitle, \
  last = -1, csv using (column(param)):(series('together', 1, 1, S(column("spectral_abscissa")))) with lines ls 3 title 'together, stable', \
  last = -1, csv using (column(param)):(series('together', 1, 0, S(column("spectral_abscissa")))) with lines ls 4 title 'together, unstable', \
  last = -1, csv using (column(param)):(series('together', 2, 1, S(column("spectral_abscissa")))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 0, S(column("spectral_abscissa")))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 1, S(column("spectral_abscissa")))) with lines ls 5 title 'opposite, stable', \
  last = -1, csv using (column(param)):(series('opposite', 1, 0, S(column("spectral_abscissa")))) with lines ls 6 title 'opposite, unstable', \
  last = -1, csv using (column(param)):(series('opposite', 2, 1, S(column("spectral_abscissa")))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 0, S(column("spectral_abscissa")))) with lines ls 6 notitle
unset multiplot
