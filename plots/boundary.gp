# Stability boundaries from `stability-scan continue --param2`: the fold (LP) and Hopf
# (HB) curves in the parameter plane, codimension-two points marked. Hopf curves are solid
# where the Hopf bifurcation is supercritical (first Lyapunov coefficient l1 < 0: crossing
# the curve, a small stable whirl grows out of the equilibrium) and dashed where it is
# subcritical (l1 > 0: no small whirl, the state jumps away); the two meet at GH points.
# Short strokes on one side of a Hopf curve mark the side where its equilibrium is stable
# (column stable_side). A legend entry only for what is drawn. Re-run with
#   gnuplot -e "curves='out/boundary_omega_d.csv'; png='b.png'; param='omega'; unit='rad/s'; param2='d'; unit2='N s/m'; title='x'; subtitle='y'" plots/boundary.gp
# Columns are read by their header names (robust to added or reordered columns): curve,
# kind, label, lyapunov, and the two parameters' symbols.
if (!exists("curves")) curves = 'out/boundary_omega_d.csv'
if (!exists("png")) png = 'boundary.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("param2")) param2 = 'd'
if (!exists("unit2")) unit2 = 'N s/m'
if (!exists("title")) title = 'stability boundaries'
if (!exists("subtitle")) subtitle = ''

set terminal pngcairo size 1100,800 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile nocolumnheaders
stats curves using (1) nooutput
set datafile columnheaders
n_rows = STATS_records - 1
nc = 0
if (n_rows > 0) { stats curves using (column("curve")) nooutput; nc = int(STATS_max) }
has_sup = 0; has_sub = 0; has_fold = 0; has_bt = 0; has_zh = 0; has_cp = 0; has_gh = 0
if (n_rows > 0) {
  stats curves using (strcol("kind") ne 'HB' ? 0 : (strcol("lyapunov") eq '' ? 0 : (real(strcol("lyapunov")) < 0 ? 1 : 0))) nooutput
  has_sup = STATS_sum > 0
  stats curves using (strcol("kind") ne 'HB' ? 0 : (strcol("lyapunov") eq '' ? 1 : (real(strcol("lyapunov")) >= 0 ? 1 : 0))) nooutput
  has_sub = STATS_sum > 0
  stats curves using (strcol("kind") eq 'LP' ? 1 : 0) nooutput
  has_fold = STATS_sum > 0
  stats curves using (strcol("label") eq 'BT' ? 1 : 0) nooutput
  has_bt = STATS_sum > 0
  stats curves using (strcol("label") eq 'ZH' ? 1 : 0) nooutput
  has_zh = STATS_sum > 0
  stats curves using (strcol("label") eq 'CP' ? 1 : 0) nooutput
  has_cp = STATS_sum > 0
  stats curves using (strcol("label") eq 'GH' ? 1 : 0) nooutput
  has_gh = STATS_sum > 0
  stats curves using (column(param)) nooutput
  xspan = STATS_max - STATS_min
  stats curves using (strcol("stable_side") eq '' ? 0 : (real(strcol("stable_side")) == 0 ? 0 : 1)) nooutput
  has_side = STATS_sum > 0
}
set xlabel sprintf('%s [%s]', param, unit)
set ylabel sprintf('%s [%s]', param2, unit2)
set format x '%.4g'
set format y '%.4g'
set grid xtics ytics mxtics mytics lc rgb '#d0d0d0', lc rgb '#eeeeee'
set mxtics
set mytics
set key outside right top spacing 1.2
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set title heading noenhanced font ',9'
# A Hopf curve point by the sign of l1 (a GH point belongs to both pieces, joining them).
hopf(k, sub) = (column("curve") == k && strcol("kind") eq 'HB') ? \
    (strcol("label") eq 'GH' ? column(param2) : \
     (strcol("lyapunov") eq '' ? (sub ? column(param2) : NaN) : \
      ((real(strcol("lyapunov")) >= 0) == sub ? column(param2) : NaN))) : NaN
fold(k) = (column("curve") == k && strcol("kind") eq 'LP') ? column(param2) : NaN
label(l) = (strcol("label") eq l) ? column(param2) : NaN
# the stroke towards the stable side: 2.5 % of the first parameter's extent
side_dx(x) = strcol("stable_side") eq '' ? NaN : (real(strcol("stable_side")) == 0 ? NaN : \
    real(strcol("stable_side")) * 0.025 * (xspan > 0 ? xspan : 1))
t(flag, text) = flag ? text : ''
if (n_rows == 0) {
  set label 1 'no fold or Hopf point in the interval: no boundary curve' at graph 0.5, graph 0.5 center
  plot 0 notitle lc rgb 'white'
} else {
plot curves using (column(param)):(column(param2)):(side_dx(0)):(0) with vectors nohead lw 5 lc rgb '#9ecae1' \
         title t(has_side, 'stable side of the Hopf curve'), \
     for [k=1:nc] curves using (column(param)):(hopf(k, 0)) with lines lw 2.5 lc rgb '#d62728' title (k == 1 ? t(has_sup, 'Hopf, supercritical (l_1 < 0)') : ''), \
     for [k=1:nc] curves using (column(param)):(hopf(k, 1)) with lines lw 2.5 dt (8,4) lc rgb '#d62728' title (k == 1 ? t(has_sub, 'Hopf, subcritical (l_1 > 0)') : ''), \
     for [k=1:nc] curves using (column(param)):(fold(k)) with lines lw 2.5 lc rgb '#1f1f1f' title (k == 1 ? t(has_fold, 'fold curves (LP)') : ''), \
     curves using (column(param)):(label('BT')) with points pt 5 ps 1.5 lc rgb '#9467bd' title t(has_bt, 'BT Bogdanov-Takens'), \
     curves using (column(param)):(label('ZH')) with points pt 9 ps 1.5 lc rgb '#ff7f0e' title t(has_zh, 'ZH zero-Hopf'), \
     curves using (column(param)):(label('CP')) with points pt 7 ps 1.5 lc rgb '#2ca02c' title t(has_cp, 'CP cusp'), \
     curves using (column(param)):(label('GH')) with points pt 13 ps 1.5 lc rgb '#17becf' title t(has_gh, 'GH generalized Hopf (l_1 = 0)')
}
