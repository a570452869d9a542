# Equilibria and periodic orbits of a continuation run against the parameter: |q| of the
# equilibrium branches (stable solid, unstable dashed) and the amplitude max |q| of the
# periodic orbits born at the Hopf points (stable cycles filled, unstable open), both in
# the rotating frame's |q| = the fixed-frame whirl radius [m] (docs/model.md §17).
# Reads the CSVs of `stability-scan continue --cycles`; re-run with
#   gnuplot -e "branches='out/branch_omega.csv'; cycles='out/cycles_omega.csv'; png='c.png'; param='omega'; unit='rad/s'; title='x'; subtitle='y'" plots/cycles.gp
# Columns by header name: branch CSV: branch, the parameter's symbol, q_abs, stable;
# cycles CSV: cycle, the parameter's symbol, amplitude, stable; cycle specials CSV (optional,
# `specials`): label, the parameter's symbol, amplitude (LPC, PD, NS marked).
if (!exists("branches")) branches = 'out/branch_omega.csv'
if (!exists("cycles")) cycles = 'out/cycles_omega.csv'
if (!exists("specials")) specials = ''
if (!exists("png")) png = 'cycles.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("title")) title = 'equilibria and periodic orbits'
if (!exists("subtitle")) subtitle = ''

set terminal pngcairo size 1100,700 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

set datafile nocolumnheaders
stats cycles using (1) nooutput
set datafile columnheaders
n_orbits = STATS_records - 1
if (n_orbits > 0) {
  stats cycles using (column(param)) nooutput
  xlo = STATS_min; xhi = STATS_max
} else {
  stats branches using (column(param)) nooutput
  xlo = STATS_min; xhi = STATS_max
}
if (xlo == xhi) { d = abs(xlo) > 0 ? 1e-6 * abs(xlo) : 1; xlo = xlo - d; xhi = xhi + d }
pad = 0.05 * (xhi - xlo)
set xrange [xlo - pad:xhi + pad]
set yrange [0:*]
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set title heading noenhanced font ',9'
set xlabel param . ' [' . unit . ']'
set ylabel '|q| of the equilibrium, max |q| of the cycle [m]'
set grid
set key outside right top spacing 1.2
set format x '%.10g'

# The cycles' special points, if there are any (a file without rows would only draw a warning).
n_sp = 0
if (specials ne '') {
  set datafile nocolumnheaders
  stats specials using (1) nooutput
  set datafile columnheaders
  n_sp = STATS_records - 1
}
special_plot = n_sp > 0 ? ", specials using (column(param)):(column(\"amplitude\")):(strcol(\"label\")) with labels point pt 5 ps 1.3 lc rgb '#000000' offset 1.5,0.5 left title 'LPC / PD / NS'" : ''
stable_eq(y) = column("stable") == 1 ? y : NaN
unstable_eq(y) = column("stable") != 1 ? y : NaN
plot branches using (column(param)):(stable_eq(column("q_abs"))) with lines lw 3 lc rgb '#1f77b4' title 'equilibria, stable', \
     branches using (column(param)):(unstable_eq(column("q_abs"))) with lines lw 2 dt 2 lc rgb '#1f77b4' title 'equilibria, unstable', \
     cycles using (column(param)):(column("stable") == 1 ? column("amplitude") : NaN) with points pt 7 ps 0.9 lc rgb '#2ca02c' title 'cycles, stable', \
     cycles using (column(param)):(column("stable") != 1 ? column("amplitude") : NaN) with points pt 6 ps 0.9 lc rgb '#d62728' title 'cycles, unstable' \
     @special_plot
