# Bifurcation diagram of a continuation of n >= 3 balls: the residual vibration |q| of
# every aligned branch against the parameter (top; stable solid and thick, unstable
# dashed; LP fold, HB Hopf and BP marked), and the balanced set's stability boundary
# (bottom): the fraction of its samples that are normally stable, a step function of the
# parameter between the samples' Hopf points (envelope_NAME.csv). Columns by header name.
# Reads the CSVs of `stability-scan continue` on an n-ball scene; re-run by hand with
#   gnuplot -e "branches='out/branch_omega.csv'; specials='out/special_omega.csv'; envelope='out/envelope_omega.csv'; png='b.png'; param='omega'; unit='rad/s'; title='x'" plots/bifurcation_n.gp
if (!exists("branches")) branches = 'out/branch_omega.csv'
if (!exists("specials")) specials = 'out/special_omega.csv'
if (!exists("envelope")) envelope = 'out/envelope_omega.csv'
if (!exists("png")) png = 'bifurcation.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("title")) title = 'continuation'
if (!exists("subtitle")) subtitle = ''
if (!exists("omega_n")) omega_n = ''

set terminal pngcairo size 1100,900 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

stats branches using (column("branch")) nooutput
nb = int(STATS_max)
aligned(k, stable_only) = (column("branch") == k && strcol("family") eq 'aligned' && \
    (!stable_only || column("stable") == 1)) ? column("q_abs") : NaN
special(lbl) = (strcol("label") eq lbl && strcol("family") eq 'aligned') ? column("q_abs") : NaN
# A legend entry only for the special points this panel draws (those of aligned branches).
n_aligned(lbl) = (strcol("label") eq lbl && strcol("family") eq 'aligned') ? 1 : 0
set datafile nocolumnheaders
stats specials using (1) nooutput
set datafile columnheaders
has_lp = 0; has_hb = 0; has_bp = 0
if (STATS_records > 1) {
  stats specials using (n_aligned('LP')) nooutput
  has_lp = STATS_sum > 0
  stats specials using (n_aligned('HB')) nooutput
  has_hb = STATS_sum > 0
  stats specials using (n_aligned('BP')) nooutput
  has_bp = STATS_sum > 0
}
t(flag, text) = flag ? text : ''

set xlabel sprintf('%s [%s]', param, unit) noenhanced
set format x '%.4g'
set grid xtics ytics mxtics mytics lc rgb '#d0d0d0', lc rgb '#eeeeee'
set mxtics
set key outside right top
set lmargin at screen 0.09
set rmargin at screen 0.76
if (omega_n ne '' && param eq 'omega') {
  set arrow 1 from first real(omega_n), graph 0 to first real(omega_n), graph 1 nohead lc rgb '#555555' dt 2 front
  set label 1 sprintf('omega_n = %.5g', real(omega_n)) at first real(omega_n), graph 0.04 offset 0.5, 0 left noenhanced front
}
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set multiplot layout 2,1 title heading noenhanced font ',9'

set logscale y
set mytics 10
set format y '10^{%T}'
set ylabel '|q| [m] of the aligned branches (rotating = fixed-frame whirl radius)'
set style line 100 lc rgb '#000000' pt 7 ps 1.2
set style line 101 lc rgb '#d62728' pt 9 ps 1.4
set style line 102 lc rgb '#9467bd' pt 5 ps 1.1
plot for [k=1:nb] branches using (column(param)):(aligned(k, 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(aligned(k, 1)) with lines lc k lw 3 notitle, \
     specials using (column(param)):(special('LP')) with points ls 100 title t(has_lp, 'LP fold'), \
     specials using (column(param)):(special('HB')) with points ls 101 title t(has_hb, 'HB Hopf'), \
     specials using (column(param)):(special('BP')) with points ls 102 title t(has_bp, 'BP branch point'), \
     NaN with lines lc rgb '#555555' lw 3 title 'stable', \
     NaN with lines lc rgb '#555555' lw 1 dt (6,4) title 'unstable'

unset logscale y
set mytics
unset label 1
set format y '%g'
set yrange [-0.05:1.05]
set ylabel 'balanced set: fraction of samples normally stable'
plot envelope using (column("from")):(column("fraction_stable")):(column("from")):(column("to")) \
       with xerrorbars lc rgb '#1f77b4' pt -1 lw 3 notitle, \
     envelope using (column("from")):(column("fraction_stable")) with steps lc rgb '#1f77b4' lw 1 notitle, \
     NaN with lines lc rgb '#1f77b4' lw 3 title 'fraction stable'
unset multiplot
