# Sweep summary chart (any number of balls, also over the ball count n): per value, the
# fraction of the balanced set that is normally stable and the number of stable aligned
# equilibria (top), and the residual vibration |q| of the best stable state (bottom; a
# stable balanced state has |q| = 0 and is drawn on the bottom edge as "balanced").
# Reads summary_NAME.csv written by `stability-scan sweep`, columns by header name; re-run by hand with
#   gnuplot -e "csv='out/summary_n.csv'; png='summary.png'; param='n'; unit='-'; logx='0'; title='x'" plots/sweep_summary.gp
if (!exists("csv")) csv = 'out/summary_n.csv'
if (!exists("png")) png = 'summary.png'
if (!exists("param")) param = 'n'
if (!exists("unit")) unit = '-'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = 'sweep summary'
if (!exists("subtitle")) subtitle = ''
# dry='1': a coulomb / stribeck scene, whose rows carry what dry friction leaves (dry_* columns)
if (!exists("dry")) dry = '0'

set terminal pngcairo size 1000,800 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

if (logx eq '1') set logscale x
if (param eq 'n') set xtics 1   # a ball count: whole numbers
set xlabel (unit eq '-' ? param : sprintf('%s [%s]', param, unit)) noenhanced
set grid
set key outside right top
set lmargin at screen 0.1
set rmargin at screen 0.72
# A legend entry only for what is drawn.
stats csv using (strcol("best_family") ne 'balanced' && strcol("best_family") ne '' ? 1 : 0) nooutput
has_aligned = STATS_sum > 0
stats csv using (strcol("best_family") eq 'balanced' ? 1 : 0) nooutput
has_balanced = STATS_sum > 0
t(flag, text) = flag ? text : ''
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set multiplot layout 2,1 title heading noenhanced font ',9'

set ylabel 'fraction of the balanced set normally stable'
set yrange [-0.05:1.05]
set y2label 'stable aligned equilibria'
stats csv using (column("aligned_stable")) nooutput
set y2range [-0.5:STATS_max + 0.5]
if (STATS_max < 10) { set y2tics 1 } else { set y2tics }   # a count: whole numbers
set ytics nomirror
plot csv using (column(param)):(column("fraction_stable")) with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'balanced set: fraction stable', \
     csv using (column(param)):(column("aligned_stable")) axes x1y2 with linespoints lw 1.5 pt 5 dt (6,4) lc rgb '#d62728' title 'aligned: number stable'

unset y2tics
stats csv using (column("aligned_stable")) nooutput
set y2range [-0.5:STATS_max + 0.5]
unset y2label
set ytics mirror
set logscale y
set mytics 10
set yrange [1e-12:1e-3]
set format y '10^{%T}'
set ylabel '|q| of the best stable state [m]'
# A stable balanced state has |q| = 0: drawn on the floor of the axis (1e-12 m).
positive(q) = (q > 0 ? q : NaN)
if (dry eq '1') {
  set ylabel '|q| [m]: best stable state (smooth law); dry friction'
  plot csv using (column(param)):(strcol("best_family") ne 'balanced' ? positive(column("best_q_abs")) : NaN) with linespoints lw 2 pt 7 lc rgb '#d62728' title t(has_aligned, 'best stable: aligned'), \
       csv using (column(param)):(strcol("best_family") eq 'balanced' ? 1e-12 : NaN) with points pt 9 ps 1.8 lc rgb '#1f77b4' title t(has_balanced, 'best stable: balanced (|q| = 0)'), \
       csv using (column(param)):(column("dry_bare_rotor_q_abs")) with lines lw 6 lc rgb '#c8c8c8' title 'rotor without balls', \
       csv using (column(param)):(column("dry_worst_q_abs")) with linespoints lw 2.5 pt 13 lc rgb '#e07b00' title 'dry friction: worst residual V'
} else {
  plot csv using (column(param)):(strcol("best_family") ne 'balanced' ? positive(column("best_q_abs")) : NaN) with linespoints lw 2 pt 7 lc rgb '#d62728' title t(has_aligned, 'best stable: aligned'), \
       csv using (column(param)):(strcol("best_family") eq 'balanced' ? 1e-12 : NaN) with points pt 9 ps 1.8 lc rgb '#1f77b4' title t(has_balanced, 'best stable: balanced (|q| = 0)')
}
unset multiplot
