# Stability boundaries from `stability-scan continue --param2`: the fold (LP) and Hopf
# (HB) curves in the parameter plane, codimension-two points marked. Re-run with
#   gnuplot -e "curves='out/boundary_omega_d.csv'; png='b.png'; param='omega'; unit='rad/s'; param2='d'; unit2='N s/m'; title='x'" plots/boundary.gp
# Columns are read by their header names (robust to added or reordered columns): curve,
# kind, label, and the two parameters' symbols.
if (!exists("curves")) curves = 'out/boundary_omega_d.csv'
if (!exists("png")) png = 'boundary.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("param2")) param2 = 'd'
if (!exists("unit2")) unit2 = 'N s/m'
if (!exists("title")) title = 'stability boundaries'

set terminal pngcairo size 1000,750 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
stats curves using (column("curve")) nooutput
nc = int(STATS_max)
set xlabel sprintf('%s [%s]', param, unit)
set ylabel sprintf('%s [%s]', param2, unit2)
set grid
set key outside right top
set title title noenhanced
on(k, kind) = (column("curve") == k && strcol("kind") eq kind) ? column(param2) : NaN
label(l) = (strcol("label") eq l) ? column(param2) : NaN
plot for [k=1:nc] curves using (column(param)):(on(k, 'HB')) with lines lw 2.5 lc rgb '#d62728' title (k == 1 ? 'Hopf curves' : ''), \
     for [k=1:nc] curves using (column(param)):(on(k, 'LP')) with lines lw 2.5 lc rgb '#1f1f1f' title (k == 1 ? 'fold curves' : ''), \
     curves using (column(param)):(label('BT')) with points pt 5 ps 1.5 lc rgb '#9467bd' title 'BT Bogdanov-Takens', \
     curves using (column(param)):(label('ZH')) with points pt 9 ps 1.5 lc rgb '#ff7f0e' title 'ZH zero-Hopf', \
     curves using (column(param)):(label('CP')) with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'CP cusp', \
     curves using (column(param)):(label('GH')) with points pt 13 ps 1.5 lc rgb '#17becf' title 'GH generalized Hopf'
