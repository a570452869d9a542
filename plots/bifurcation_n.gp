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

set xlabel sprintf('%s [%s]', param, unit) noenhanced
set grid
set key outside right top
set lmargin at screen 0.09
set rmargin at screen 0.76
set multiplot layout 2,1 title title noenhanced

set logscale y
set format y '10^{%T}'
set ylabel '|q| [m] of the aligned branches (rotating = fixed-frame whirl radius)'
set style line 100 lc rgb '#000000' pt 7 ps 1.2
set style line 101 lc rgb '#d62728' pt 9 ps 1.4
set style line 102 lc rgb '#9467bd' pt 5 ps 1.1
plot for [k=1:nb] branches using (column(param)):(aligned(k, 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(aligned(k, 1)) with lines lc k lw 3 notitle, \
     specials using (column(param)):(special('LP')) with points ls 100 title 'LP fold', \
     specials using (column(param)):(special('HB')) with points ls 101 title 'HB Hopf', \
     specials using (column(param)):(special('BP')) with points ls 102 title 'BP branch point', \
     NaN with lines lc rgb '#555555' lw 3 title 'stable', \
     NaN with lines lc rgb '#555555' lw 1 dt (6,4) title 'unstable'

unset logscale y
set format y '%g'
set yrange [-0.05:1.05]
set ylabel 'balanced set: fraction of samples normally stable'
plot envelope using (column("from")):(column("fraction_stable")):(column("from")):(column("to")) \
       with xerrorbars lc rgb '#1f77b4' pt -1 lw 3 notitle, \
     envelope using (column("from")):(column("fraction_stable")) with steps lc rgb '#1f77b4' lw 1 notitle, \
     NaN with lines lc rgb '#1f77b4' lw 3 title 'fraction stable'
unset multiplot
