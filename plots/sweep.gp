# Sweep chart: |q| and the spectral abscissa against the swept parameter, one colour
# per equilibrium family (both members of a family share it), stable solid, unstable
# dashed; a legend entry only for what is drawn. Speed sweeps (omega) get an rpm axis on
# top and omega_n marked (`omega_n`, if given). Reads the CSV written by
# `stability-scan sweep`; re-run by hand with
#   gnuplot -e "csv='out/sweep_omega.csv'; png='sweep.png'; param='omega'; unit='rad/s'; logx='0'; title='x'; subtitle='y'; omega_n='249.93'" plots/sweep.gp
# Columns are read by their header names: step, the parameter's symbol, family, member, q_abs [m],
# spectral_abscissa [1/s], stable.
if (!exists("csv")) csv = 'out/sweep_omega.csv'
if (!exists("png")) png = 'sweep.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = 'sweep'
if (!exists("subtitle")) subtitle = ''
if (!exists("omega_n")) omega_n = ''
# dry='1': a coulomb / stribeck scene, whose rows carry what dry friction leaves (dry_* columns,
# the same on every row of a value: `smooth unique` draws one point a value)
if (!exists("dry")) dry = '0'

set terminal pngcairo size 1200,950 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

# A series is one (family, member); it is drawn only where its stability matches `st`.
# The line breaks where the series is absent at some values (the step index jumps).
series(fam, mem, st, y) = (strcol("family") eq fam && column("member") == mem) ? \
    (gap = (last >= 0 && column("step") != last + 1), last = column("step"), \
     (column("stable") == st && !gap) ? y : NaN) : NaN

# Which (family, stability) pairs occur: a legend entry only for those.
count(fam, st) = (strcol("family") eq fam && column("stable") == st) ? 1 : 0
stats csv using (count('balanced', 1)) nooutput
has_b1 = STATS_sum > 0
stats csv using (count('balanced', 0)) nooutput
has_b0 = STATS_sum > 0
stats csv using (count('together', 1)) nooutput
has_t1 = STATS_sum > 0
stats csv using (count('together', 0)) nooutput
has_t0 = STATS_sum > 0
stats csv using (count('opposite', 1)) nooutput
has_o1 = STATS_sum > 0
stats csv using (count('opposite', 0)) nooutput
has_o0 = STATS_sum > 0
stats csv using ((strcol("family") ne 'balanced' && column("q_abs") > 0) ? 1 : 0) nooutput
has_q = STATS_sum > 0
stats csv using (column(param)) nooutput
xlo = STATS_min
xhi = STATS_max
if (xlo == xhi) { xlo = xlo * 0.9; xhi = xhi * 1.1 + (xhi == 0) }
set xrange [xlo:xhi]
t(flag, text) = flag ? text : ''

# Signed log for the abscissa, which spans -10 .. +1e-7 1/s and whose sign is the point:
# S(a) = sgn(a) log10(1 + |a| / a0), with a0 = 1e-9 1/s.
a0 = 1e-9
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

if (logx eq '1') { set logscale x; set mxtics 10 } else { set mxtics }
set xlabel sprintf('%s [%s]', param, unit)
set format x '%.4g'
set grid xtics ytics mxtics mytics lc rgb '#d0d0d0', lc rgb '#eeeeee'
set key outside right top spacing 1.2
set lmargin at screen 0.10
set rmargin at screen 0.72
if (omega_n ne '' && param eq 'omega') {
  set arrow 1 from first real(omega_n), graph 0 to first real(omega_n), graph 1 nohead lc rgb '#555555' dt 2 front
  set label 1 sprintf('omega_n = %.5g rad/s', real(omega_n)) at first real(omega_n), graph 0.04 offset 0.5, 0 left noenhanced front
}
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set multiplot layout 2,1 title heading noenhanced font ',9'

if (param eq 'omega') {
  if (logx eq '1') {
    # a log axis cannot be linked: the same proportions by the range
    set x2range [xlo * 30 / pi : xhi * 30 / pi]
    set logscale x2
    set x2tics nomirror
  } else {
    set link x2 via x * 30 / pi inverse x * pi / 30
    # rpm tics at round values (1, 2 or 5 times a power of ten, about 8 of them)
    r = (xhi - xlo) * 30 / pi / 8
    r10 = 10.0**floor(log10(r))
    rpm_step = (r / r10 < 1.5 ? 1 : r / r10 < 3.5 ? 2 : r / r10 < 7.5 ? 5 : 10) * r10
    set x2tics nomirror rpm_step
  }
  set mx2tics
  set x2label 'speed [rpm]' offset 0, -0.5
}
set logscale y
set mytics 10
set ylabel '|q| [m] (rotor excursion = whirl radius; balanced: q = 0, not drawn)'
set format y '10^{%T}'
if (dry eq '1') {
set ylabel '|q| [m]: equilibria (smooth law); dry friction'
plot \
  csv using (column(param)):(column("dry_bare_rotor_q_abs")) smooth unique with lines lw 6 lc rgb '#c8c8c8' title 'rotor without balls', \
  csv using (column(param)):(column("dry_worst_q_abs")) smooth unique with lines lw 3 lc rgb '#e07b00' title 'dry friction: worst residual V', \
  last = -1, csv using (column(param)):(series('together', 1, 1, column("q_abs"))) with lines ls 3 title t(has_t1, 'together, stable'), \
  last = -1, csv using (column(param)):(series('together', 1, 0, column("q_abs"))) with lines ls 4 title t(has_t0, 'together, unstable'), \
  last = -1, csv using (column(param)):(series('together', 2, 1, column("q_abs"))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 0, column("q_abs"))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 1, column("q_abs"))) with lines ls 5 title t(has_o1, 'opposite, stable'), \
  last = -1, csv using (column(param)):(series('opposite', 1, 0, column("q_abs"))) with lines ls 6 title t(has_o0, 'opposite, unstable'), \
  last = -1, csv using (column(param)):(series('opposite', 2, 1, column("q_abs"))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 0, column("q_abs"))) with lines ls 6 notitle
} else { if (has_q) {
plot \
  last = -1, csv using (column(param)):(series('together', 1, 1, column("q_abs"))) with lines ls 3 title t(has_t1, 'together, stable'), \
  last = -1, csv using (column(param)):(series('together', 1, 0, column("q_abs"))) with lines ls 4 title t(has_t0, 'together, unstable'), \
  last = -1, csv using (column(param)):(series('together', 2, 1, column("q_abs"))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 0, column("q_abs"))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 1, column("q_abs"))) with lines ls 5 title t(has_o1, 'opposite, stable'), \
  last = -1, csv using (column(param)):(series('opposite', 1, 0, column("q_abs"))) with lines ls 6 title t(has_o0, 'opposite, unstable'), \
  last = -1, csv using (column(param)):(series('opposite', 2, 1, column("q_abs"))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 0, column("q_abs"))) with lines ls 6 notitle
} else {
  set yrange [1e-9:1e-3]
  set label 2 'no state with q != 0' at graph 0.5, graph 0.5 center
  plot 1e-20 notitle
  unset label 2
  set yrange [*:*]
} }
if (param eq 'omega') {
  unset x2tics
  unset x2label
  if (logx ne '1') { unset link x2 }
  unset logscale x2
}
unset logscale y
set format y '%g'
unset label 1

# The stable half (a < 0: perturbations decay) and the unstable half shaded.
set object 1 rectangle from graph 0, first 0 to graph 1, graph 1 behind fc rgb '#fbe3e3' fs solid noborder
set object 2 rectangle from graph 0, graph 0 to graph 1, first 0 behind fc rgb '#e3eefb' fs solid noborder
set label 3 'unstable: a > 0, perturbations grow' at graph 0.01, graph 0.95 left front
set label 4 'stable: a < 0, they decay in about 1/|a| s' at graph 0.01, graph 0.05 left front
set ylabel "spectral abscissa a = max Re(lambda) [1/s]\n(signed log: sgn(a) log_{10}(1 + |a| / 10^{-9}))"
set ytics ('0' 0)
do for [e = -8:2:2] {
  set ytics add (sprintf('10^{%d}', e) S(10.0**e), sprintf('-10^{%d}', e) S(-(10.0**e)))
}
set mytics 2
set arrow 2 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  last = -1, csv using (column(param)):(series('balanced', 1, 1, S(column("spectral_abscissa")))) with lines ls 1 title t(has_b1, 'balanced, stable'), \
  last = -1, csv using (column(param)):(series('balanced', 1, 0, S(column("spectral_abscissa")))) with lines ls 2 title t(has_b0, 'balanced, unstable'), \
  last = -1, csv using (column(param)):(series('balanced', 2, 1, S(column("spectral_abscissa")))) with lines ls 1 notitle, \
  last = -1, csv using (column(param)):(series('balanced', 2, 0, S(column("spectral_abscissa")))) with lines ls 2 notitle, \
  last = -1, csv using (column(param)):(series('together', 1, 1, S(column("spectral_abscissa")))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 1, 0, S(column("spectral_abscissa")))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 1, S(column("spectral_abscissa")))) with lines ls 3 notitle, \
  last = -1, csv using (column(param)):(series('together', 2, 0, S(column("spectral_abscissa")))) with lines ls 4 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 1, S(column("spectral_abscissa")))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 1, 0, S(column("spectral_abscissa")))) with lines ls 6 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 1, S(column("spectral_abscissa")))) with lines ls 5 notitle, \
  last = -1, csv using (column(param)):(series('opposite', 2, 0, S(column("spectral_abscissa")))) with lines ls 6 notitle
unset multiplot
