# Stick set of set-valued Coulomb friction on the torus (beta1, beta2), two balls
# (model.md §14): shaded where every ball can stick (a raster, for the fill only), the
# traced boundary curves on top (s_i = +1 solid, s_i = -1 dashed; ball 1 blue, ball 2 red),
# the balanced points (black circles), the other smooth equilibria (triangles) and where
# the worst residual vibration V is attained (star). Written by
# `stability-scan equilibria SCENE --stick-set DIR`; re-run by hand with
#   gnuplot -e "csv='DIR/stick_boundary.csv'; raster='DIR/stick_raster.dat'; seeds='DIR/stick_seeds.dat'; png='x.png'" plots/stick_set.gp
if (!exists("csv")) csv = 'out/stick_boundary.csv'
if (!exists("raster")) raster = 'out/stick_raster.dat'
if (!exists("seeds")) seeds = 'out/stick_seeds.dat'
if (!exists("png")) png = 'stick_set.png'
if (!exists("title")) title = 'stick set'
if (!exists("subtitle")) subtitle = ''
if (!exists("worst1")) worst1 = '-10'
if (!exists("worst2")) worst2 = '-10'

set terminal pngcairo size 900,860 enhanced font 'DejaVu Sans,10'
set output png
set title sprintf("%s\n%s", title, subtitle) noenhanced
set xlabel 'beta_1 [rad]'
set ylabel 'beta_2 [rad]'
set xrange [0:2*pi]
set yrange [0:2*pi]
set size ratio -1
set xtics ('0' 0, 'π/2' pi/2, 'π' pi, '3π/2' 3*pi/2, '2π' 2*pi)
set ytics ('0' 0, 'π/2' pi/2, 'π' pi, '3π/2' 3*pi/2, '2π' 2*pi)
set grid front
set key outside below horizontal
set palette defined (0 'white', 1 '#c8e6c9')
unset colorbox
set cbrange [0:1]
set datafile commentschars '#'
set datafile separator ','
plot raster using 1:2:3 with image notitle, \
     csv using 4:(column(2) == 1 && column(3) > 0 ? column(5) : NaN) with lines lw 2 lc rgb '#1565c0' dt 1 title 'ball 1: s_1 = +1', \
     csv using 4:(column(2) == 1 && column(3) < 0 ? column(5) : NaN) with lines lw 2 lc rgb '#1565c0' dt 2 title 'ball 1: s_1 = -1', \
     csv using 4:(column(2) == 2 && column(3) > 0 ? column(5) : NaN) with lines lw 2 lc rgb '#c62828' dt 1 title 'ball 2: s_2 = +1', \
     csv using 4:(column(2) == 2 && column(3) < 0 ? column(5) : NaN) with lines lw 2 lc rgb '#c62828' dt 2 title 'ball 2: s_2 = -1', \
     seeds using 1:($3 == 1 ? $2 : NaN) with points pt 7 ps 1.4 lc rgb 'black' title 'balanced point', \
     seeds using 1:($3 == 2 ? $2 : NaN) with points pt 9 ps 1.4 lc rgb '#555555' title 'other smooth equilibrium', \
     '+' using (real(worst1)):(real(worst2)) every ::0::0 with points pt 3 ps 2.5 lw 2 lc rgb '#ff6f00' title 'worst |q| (V)'
