# Bifurcation diagram of a continuation run, three panels against the parameter:
#   |q| of every branch off the balanced family (log; balanced branches have q = 0),
#   the spectral abscissa max Re(lambda) of every branch (signed log: its sign is the
#   stability), and beta1.
# One colour per branch (the legend names its family); stable solid and thick, unstable
# dashed; special points marked: LP fold, BP branch point, HB Hopf, supercritical (first
# Lyapunov coefficient l1 < 0: a small stable whirl grows out of the lost equilibrium)
# filled, subcritical (l1 > 0: no small whirl, the machine jumps away) open. The branch
# CSV has a row at each special point, so the line style changes exactly there. Speed
# axes (omega) get an rpm axis on top and omega_n marked (`omega_n`, if given).
# Reads the CSVs of `stability-scan continue`; re-run with
#   gnuplot -e "branches='out/branch_omega.csv'; specials='out/special_omega.csv'; png='b.png'; param='omega'; unit='rad/s'; title='x'; subtitle='y'; omega_n='249.93'" plots/bifurcation.gp
# Columns are read by their header names (robust to added or reordered columns):
#   branch CSV: branch, point, the parameter's symbol, beta1, q_abs, family, stable, re1..re8
#   special CSV: label, the parameter's symbol, beta1, q_abs, family, lyapunov
if (!exists("branches")) branches = 'out/branch_omega.csv'
if (!exists("specials")) specials = 'out/special_omega.csv'
if (!exists("png")) png = 'bifurcation.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("title")) title = 'continuation'
if (!exists("subtitle")) subtitle = ''
if (!exists("omega_n")) omega_n = ''

set terminal pngcairo size 1200,1150 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

stats branches using (column("branch")) nooutput
nb = int(STATS_max)
# The family of each branch (from its first row), for the legend.
fams = ''
stats branches using (fams = column("point") == 0 ? fams . ' ' . strcol("family") : fams, 0) nooutput
# The parameter's range; whether any point is off the balanced family (the |q| panel).
stats branches using (column(param)) nooutput
xlo = STATS_min
xhi = STATS_max
stats branches using ((strcol("family") ne 'balanced' && column("q_abs") > 0) ? 1 : 0) nooutput
has_q = (STATS_max > 0)
if (xlo == xhi) { xlo = xlo - 1; xhi = xhi + 1 }
set xrange [xlo:xhi]

# y on branch k (NaN elsewhere); `stable_only` keeps only stable points. Lines break where
# the wrapped angle jumps by more than pi, and between branches.
on(k, y, stable_only) = (column("branch") == k && (!stable_only || column("stable") == 1)) ? y : NaN
angle(k, stable_only) = (column("branch") == k) ? \
    (jump = (last_k == k && abs(column("beta1") - last_b) > pi), last_k = k, last_b = column("beta1"), \
     (jump || (stable_only && column("stable") != 1)) ? NaN : column("beta1")) : NaN
# |q| of a point off the balanced family (balanced points have q = 0: off the log axis).
off_balanced(y) = (strcol("family") eq 'balanced' || y <= 0) ? NaN : y
# The spectral abscissa from the eigenvalue columns, on a signed log scale:
# S(a) = sgn(a) log10(1 + |a| / a0), a0 = 1e-9 1/s (it spans -100 .. +10 1/s, the sign is the point).
mx(a, b) = a > b ? a : b
abscissa = 'mx(mx(mx(column("re1"), column("re2")), mx(column("re3"), column("re4"))), mx(mx(column("re5"), column("re6")), mx(column("re7"), column("re8"))))'
a0 = 1e-9
S(a) = sgn(a) * log10(1 + abs(a) / a0)

set style line 100 lc rgb '#000000' pt 7 ps 1.4
set style line 101 lc rgb '#d62728' pt 9 ps 1.8
set style line 102 lc rgb '#d62728' pt 8 ps 1.8 lw 2
set style line 103 lc rgb '#d62728' pt 2 ps 1.8 lw 2
set style line 104 lc rgb '#9467bd' pt 5 ps 1.3
# HB by the sign of l1 (empty where the Hopf system did not converge).
hopf(sign, y) = (strcol("label") ne 'HB') ? NaN : \
    (sign == 0 ? (strcol("lyapunov") eq '' ? y : NaN) : (strcol("lyapunov") ne '' && sgn(real(strcol("lyapunov"))) == sign ? y : NaN))
special(lbl, y) = (strcol("label") eq lbl) ? y : NaN
# Which kinds of special point there are: a legend entry and a plot element only for those
# (a file with no rows at all would only draw a warning).
set datafile nocolumnheaders
stats specials using (1) nooutput
set datafile columnheaders
n_specials = STATS_records - 1
has_lp = 0; has_bp = 0; has_sup = 0; has_sub = 0; has_hb0 = 0
if (n_specials > 0) {
  stats specials using (strcol("label") eq 'LP' ? 1 : 0) nooutput
  has_lp = STATS_sum > 0
  stats specials using (strcol("label") eq 'BP' ? 1 : 0) nooutput
  has_bp = STATS_sum > 0
  stats specials using (hopf(-1, 1) == 1 ? 1 : 0) nooutput
  has_sup = STATS_sum > 0
  stats specials using (hopf(1, 1) == 1 ? 1 : 0) nooutput
  has_sub = STATS_sum > 0
  stats specials using (hopf(0, 1) == 1 ? 1 : 0) nooutput
  has_hb0 = STATS_sum > 0
}
# The special points of one panel, y given as an expression of the row (a string).
marks(y, titled) = \
  (has_lp ? sprintf(", specials using (column(param)):(special('LP', %s)) with points ls 100 %s", y, titled ? "title 'LP fold'" : 'notitle') : '') . \
  (has_sup ? sprintf(", specials using (column(param)):(hopf(-1, %s)) with points ls 101 %s", y, titled ? "title 'HB supercritical (l_1 < 0)'" : 'notitle') : '') . \
  (has_sub ? sprintf(", specials using (column(param)):(hopf(1, %s)) with points ls 102 %s", y, titled ? "title 'HB subcritical (l_1 > 0)'" : 'notitle') : '') . \
  (has_hb0 ? sprintf(", specials using (column(param)):(hopf(0, %s)) with points ls 103 %s", y, titled ? "title 'HB (l_1 not computed)'" : 'notitle') : '') . \
  (has_bp ? sprintf(", specials using (column(param)):(special('BP', %s)) with points ls 104 %s", y, titled ? "title 'BP branch point'" : 'notitle') : '')

set xlabel sprintf('%s [%s]', param, unit)
set format x '%.4g'
set grid xtics ytics mxtics mytics lc rgb '#dddddd', lc rgb '#f0f0f0'
set mxtics
set key outside right top spacing 1.2
set lmargin at screen 0.09
set rmargin at screen 0.70
if (omega_n ne '' && param eq 'omega') {
  set arrow 1 from first real(omega_n), graph 0 to first real(omega_n), graph 1 nohead lc rgb '#555555' dt 2
  set label 1 sprintf('omega_n = %.5g', real(omega_n)) at first real(omega_n), graph 0.04 offset 0.5, 0 left noenhanced front
}
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set multiplot layout 3,1 title heading noenhanced font ',9'

# ---- panel 1: |q| -------------------------------------------------------------------------
if (param eq 'omega') {
  set link x2 via x * 30 / pi inverse x * pi / 30
  # rpm tics at round values (1, 2 or 5 times a power of ten, about 8 of them)
  r = (xhi - xlo) * 30 / pi / 8
  r10 = 10.0**floor(log10(r))
  rpm_step = (r / r10 < 1.5 ? 1 : r / r10 < 3.5 ? 2 : r / r10 < 7.5 ? 5 : 10) * r10
  set x2tics nomirror rpm_step
  set mx2tics
  set x2label 'speed [rpm]' offset 0, -0.5
}
set logscale y
set format y '10^{%T}'
set mytics 10
set ylabel '|q| [m] (rotating frame; also the whirl radius)'
MARKS = marks('off_balanced(column("q_abs"))', 0)
if (has_q) {
  plot for [k=1:nb] branches using (column(param)):(on(k, off_balanced(column("q_abs")), 0)) with lines lc k lw 1 dt (6,4) notitle, \
       for [k=1:nb] branches using (column(param)):(on(k, off_balanced(column("q_abs")), 1)) with lines lc k lw 3 notitle \
       @MARKS
} else {
  set yrange [1e-9:1e-3]
  set label 2 'every branch is balanced (q = 0): nothing to draw on this log axis' at graph 0.5, graph 0.5 center noenhanced
  plot 1e-20 notitle
  unset label 2
  set yrange [*:*]
}
if (param eq 'omega') {
  unset x2tics
  unset x2label
  unset link x2
}
unset logscale y
set mytics default
set format y '%g'
unset arrow 1
unset label 1

# ---- panel 2: spectral abscissa -------------------------------------------------------------
if (omega_n ne '' && param eq 'omega') {
  set arrow 1 from first real(omega_n), graph 0 to first real(omega_n), graph 1 nohead lc rgb '#555555' dt 2
}
set ylabel "spectral abscissa max Re(lambda) [1/s]\nsgn(a) log_{10}(1 + |a| / 10^{-9})"
set ytics ('0' 0)
do for [e = -8:2:2] {
  set ytics add (sprintf('10^{%d}', e) S(10.0**e), sprintf('-10^{%d}', e) S(-(10.0**e)))
}
set arrow 2 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
MARKS = marks('0', 1)
plot for [k=1:nb] branches using (column(param)):(on(k, S(@abscissa), 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(on(k, S(@abscissa), 1)) with lines lc k lw 3 \
         title sprintf('branch %d: %s', k, word(fams, k)), \
     NaN with lines lc rgb '#000000' lw 3 title 'stable (solid)', \
     NaN with lines lc rgb '#000000' lw 1 dt (6,4) title 'unstable (dashed)' \
     @MARKS
unset arrow 2
unset arrow 1
set ytics autofreq

# ---- panel 3: beta1 ------------------------------------------------------------------------
if (omega_n ne '' && param eq 'omega') {
  set arrow 1 from first real(omega_n), graph 0 to first real(omega_n), graph 1 nohead lc rgb '#555555' dt 2
}
set ylabel 'beta1 [rad] (ball 1, rotating frame)'
set yrange [0:2*pi]
set ytics ('0' 0, 'pi/2' pi/2, 'pi' pi, '3pi/2' 3*pi/2, '2pi' 2*pi)
set mytics 2
MARKS = marks('column("beta1")', 0)
plot for [k=1:nb] branches using (column(param)):(last_k = -1, angle(k, 0)) with lines lc k lw 1 dt (6,4) notitle, \
     for [k=1:nb] branches using (column(param)):(angle(k, 1)) with lines lc k lw 3 notitle \
     @MARKS
unset multiplot
