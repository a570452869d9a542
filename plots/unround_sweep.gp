# Sweep on an unround race (model.md §11.10): the residual whirl |q| of every equilibrium of
# the complete search per value (stable filled, unstable open), the design figure (|q| of
# the best stable state, line) and the bare rotor's whirl (grey), with the first-order
# regime Lambda <= 0.1 of §11.6 shaded. Columns by header name. Re-run by hand with
#   gnuplot -e "csv='out/sweep_omega.csv'; summary='out/summary_omega.csv'; png='s.png'; param='omega'; unit='rad/s'; logx='0'; title='x'" plots/unround_sweep.gp
if (!exists("csv")) csv = 'out/sweep_unroundness.csv'
if (!exists("summary")) summary = 'out/summary_unroundness.csv'
if (!exists("png")) png = 'unround_sweep.png'
if (!exists("param")) param = 'unroundness'
if (!exists("unit")) unit = '-'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = 'unround race sweep'
if (!exists("subtitle")) subtitle = ''
# A flexible shaft's sweep (model.md §18.18) has no first-order regime column and other labels.
if (!exists("first_order")) first_order = '1'
if (!exists("bare")) bare = 'bare rotor'
if (!exists("open")) open = 'unstable equilibrium'

set terminal pngcairo size 1100,720 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set title heading noenhanced font ',8'
if (logx eq '1') set logscale x
set xlabel (unit eq '-' ? sprintf('%s (factor on every race amplitude)', param) : sprintf('%s [%s]', param, unit)) noenhanced
set ylabel 'residual whirl |q| [m] (fixed frame)'
set logscale y
set format y '10^{%T}'
set grid
# The key below the plot: the title then centres on the whole width (a shaft's subtitle is long).
set key outside bottom center horizontal
set y2range [0:1]
unset y2tics
set style fill transparent solid 0.15 noborder
has_first = 0
if (first_order eq '1') { stats summary using (column("first_order")) nooutput; has_first = STATS_sum > 0 }
positive(q) = (q > 0 ? q : NaN)
# The shaded regime only where it exists: a plot of no drawable point would abort the whole chart.
shade = has_first ? "summary using (column(param)):(column('first_order') > 0 ? 1 : NaN) axes x1y2 with boxes lc rgb '#2ca02c' title 'first-order regime (Lambda <= 0.1)'," : ""
plot @shade \
     csv using (column(param)):(column("stable") == 0 ? positive(column("q_abs")) : NaN) with points pt 6 ps 0.6 lc rgb '#7f7f7f' title open, \
     csv using (column(param)):(column("stable") == 1 ? positive(column("q_abs")) : NaN) with points pt 7 ps 0.6 lc rgb '#1f77b4' title 'stable equilibrium', \
     summary using (column(param)):(positive(column("best_q_abs"))) with linespoints lw 2 pt 7 ps 0.4 lc rgb '#d62728' title 'best stable |q| (design figure)', \
     summary using (column(param)):(column("q_bare")) with lines lw 1 dt (6,4) lc rgb '#444444' title bare
