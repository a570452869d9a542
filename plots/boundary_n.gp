# Stability boundaries of n >= 3 balls in two parameters: the fold curves (black) and the
# Hopf curves of the aligned branches (red), and the Hopf curves of the balanced set's
# samples (blue): the set's stability boundary is the band they span (docs/model.md
# §13.7). Reads boundary_P1_P2.csv of `stability-scan continue --param2` on an n-ball
# scene, columns by header name; re-run by hand with
#   gnuplot -e "curves='out/boundary_omega_mu.csv'; png='b.png'; param='omega'; unit='rad/s'; param2='mu'; unit2='-'; title='x'" plots/boundary_n.gp
if (!exists("curves")) curves = 'out/boundary_omega_mu.csv'
if (!exists("png")) png = 'boundary.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("param2")) param2 = 'mu'
if (!exists("unit2")) unit2 = '-'
if (!exists("title")) title = 'stability boundaries'

set terminal pngcairo size 1000,750 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

stats curves using (column("curve")) nooutput
nc = int(STATS_max)
on(k, kind, family) = (column("curve") == k && strcol("kind") eq kind && strcol("family") eq family) ? column(param2) : NaN
mark(lbl) = strcol("label") eq lbl ? column(param2) : NaN

set xlabel sprintf('%s [%s]', param, unit) noenhanced
set ylabel (unit2 eq '-' ? param2 : sprintf('%s [%s]', param2, unit2)) noenhanced
set title title noenhanced
set grid
set format x '%g'
set format y '%g'
set key outside right top
set rmargin at screen 0.75
plot for [k=1:nc] curves using (column(param)):(on(k, 'HB', 'balanced')) with lines lc rgb '#1f77b4' lw 1 notitle, \
     for [k=1:nc] curves using (column(param)):(on(k, 'HB', 'aligned')) with lines lc rgb '#d62728' lw 2 notitle, \
     for [k=1:nc] curves using (column(param)):(on(k, 'LP', 'aligned')) with lines lc rgb '#000000' lw 2 notitle, \
     curves using (column(param)):(mark('BT')) with points pt 7 ps 1.3 lc rgb '#9467bd' title 'BT (Hopf frequency -> 0)', \
     NaN with lines lc rgb '#1f77b4' lw 2 title 'Hopf, balanced samples', \
     NaN with lines lc rgb '#d62728' lw 2 title 'Hopf, aligned', \
     NaN with lines lc rgb '#000000' lw 2 title 'fold, aligned'
