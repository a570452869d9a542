# Mode shapes (docs/views.md): for one equilibrium, one panel per mode: the race (circle of
# radius 1 = l_1), the bodies' places (black), and one cycle of the rotor centre (red) and of each ball
# centre (blue) in the rotating frame (a1 toward the unbalance), displacements scaled so that
# the largest of a mode is 0.25. Reads modes.csv of `stability-scan equilibria --mode-shapes DIR`:
#   gnuplot -e "csv='DIR/modes.csv'; png='m.png'; equilibrium=1; count=4; title='x'; t1='mode 1'" plots/modes.gp
if (!exists("csv")) csv = 'modes.csv'
if (!exists("png")) png = 'modes.png'
if (!exists("equilibrium")) equilibrium = 1
if (!exists("count")) count = 4
if (!exists("title")) title = 'mode shapes'
equilibrium = equilibrium + 0
count = count + 0

cols = ceil(sqrt(count))
rows = ceil(count * 1.0 / cols)
set terminal pngcairo size (340 * cols + 40),(340 * rows + 60) enhanced font 'DejaVu Sans,9'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set size ratio -1
set xrange [-1.45:1.45]
set yrange [-1.45:1.45]
set parametric
set trange [0:2*pi]
set xtics 0.5
set ytics 0.5
set grid
set key bottom right font ',8'
set multiplot layout rows,cols title title noenhanced

pick(m, body, v) = (column("equilibrium") == equilibrium && column("mode") == m && strcol("body") eq body) ? v : NaN
place(m, v) = (column("equilibrium") == equilibrium && column("mode") == m && column("theta") == 0) ? v : NaN

# The CSV numbers modes among all pairs; the k-th drawn mode is the k-th distinct mode number.
do for [k = 1:count] {
  ttl = exists(sprintf('t%d', k)) ? value(sprintf('t%d', k)) : sprintf('mode %d', k)
  m = 0 + substr(ttl, 6, strstrt(ttl, ':') - 1)
  set title ttl noenhanced font ',8'
  plot cos(t), sin(t) with lines lc rgb '#bbbbbb' dt 2 notitle, \
       csv using (pick(m, 'rotor', column("x"))):(pick(m, 'rotor', column("y"))) with lines lc rgb '#d62728' lw 2 title 'rotor centre', \
       for [b = 1:12] csv using (pick(m, sprintf('ball%d', b), column("x"))):(pick(m, sprintf('ball%d', b), column("y"))) with lines lc rgb '#1f77b4' lw 1.5 title (b == 1 ? 'ball centres' : ''), \
       csv using (place(m, column("x0"))):(place(m, column("y0"))) with points pt 7 ps 0.7 lc rgb 'black' title 'places (equilibrium)'
}
unset multiplot
