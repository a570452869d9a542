# Bifurcation diagram of a continuation run: |q| and beta1 of every branch against the
# parameter, stable solid (thick), unstable dashed, special points marked (LP fold,
# BP branch point, HB Hopf). Reads the CSVs of `stability-scan continue`; re-run with
#   gnuplot -e "branches='out/branch_omega.csv'; specials='out/special_omega.csv'; png='b.png'; param='omega'; unit='rad/s'; title='x'" plots/bifurcation.gp
# Columns are read by their header names (robust to added or reordered columns):
#   branch CSV: branch, the parameter's symbol, beta1, q_abs, family, stable
#   special CSV: label, the parameter's symbol, beta1, q_abs, family
if (!exists("branches")) branches = 'out/branch_omega.csv'
if (!exists("specials")) specials = 'out/special_omega.csv'
if (!exists("png")) png = 'bifurcation.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("title")) title = 'continuation'

set terminal pngcairo size 1100,900 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

stats branches using (column("branch")) nooutput
nb = int(STATS_max)

# y on branch k (NaN elsewhere); `stable_only` keeps only stable points. Lines break where
# the wrapped angle jumps by more than pi, and between branches.
on(k, y, stable_only) = (column("branch") == k && (!stable_only || column("stable") == 1)) ? y : NaN
angle(k, stable_only) = (column("branch") == k) ? \
    (jump = (last_k == k && abs(column("beta1") - last_b) > pi), last_k = k, last_b = column("beta1"), \
     (jump || (stable_only && column("stable") != 1)) ? NaN : column("beta1")) : NaN
set style line 100 lc rgb '#000000' pt 7 ps 1.4
set style line 101 lc rgb '#d62728' pt 9 ps 1.6
set style line 102 lc rgb '#9467bd' pt 5 ps 1.3
special(lbl, y) = (strcol("label") eq lbl) ? y : NaN
# |q| of a point off the balanced family (balanced points have q = 0: off the log axis).
off_balanced(y) = strcol("family") eq 'balanced' ? NaN : y

set xlabel sprintf('%s [%s]', param, unit)
set grid
set key outside right top
set lmargin at screen 0.09
set rmargin at screen 0.78
set multiplot layout 2,1 title title noenhanced

set logscale y
set format y '10^{%T}'
set ylabel '|q| [m] (balanced branches, q = 0, are off this axis)'
plot for [k=1:nb] branches using (column(param)):(on(k, off_balanced(column("q_abs")), 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(on(k, off_balanced(column("q_abs")), 1)) with lines lc k lw 3 title sprintf('branch %d', k), \
     specials using (column(param)):(special('LP', off_balanced(column("q_abs")))) with points ls 100 title 'LP fold', \
     specials using (column(param)):(special('HB', off_balanced(column("q_abs")))) with points ls 101 title 'HB Hopf', \
     specials using (column(param)):(special('BP', off_balanced(column("q_abs")))) with points ls 102 title 'BP branch point'

unset logscale y
set format y '%g'
set ylabel 'beta1 [rad]'
set yrange [0:2*pi]
set ytics ('0' 0, 'pi/2' pi/2, 'pi' pi, '3pi/2' 3*pi/2, '2pi' 2*pi)
plot for [k=1:nb] branches using (column(param)):(last_k = -1, angle(k, 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(angle(k, 1)) with lines lc k lw 3 notitle, \
     specials using (column(param)):(special('LP', column("beta1"))) with points ls 100 notitle, \
     specials using (column(param)):(special('HB', column("beta1"))) with points ls 101 notitle, \
     specials using (column(param)):(special('BP', column("beta1"))) with points ls 102 notitle
unset multiplot
