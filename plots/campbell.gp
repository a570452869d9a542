# Campbell diagram (docs/views.md): signed fixed-frame whirl frequencies of one equilibrium
# family against the speed (forward > 0, backward < 0), the 1X line, omega_n and the
# critical speeds where a rotor forward-whirl mode crosses 1X; below it the damping ratio
# and the logarithmic decrement of every mode (signed log scales: < 0 is a growing mode).
# Reads campbell_omega.csv of `stability-scan sweep|continue ... --param omega`; by hand:
#   gnuplot -e "csv='out/campbell_omega.csv'; png='c.png'; unit='rad/s'; family='balanced'; critical='249.8'; omega_n='249.93'; title='x'" plots/campbell.gp
# Columns by header name: speed, family, label, whirl_display, whirl, zeta, log_decrement.
if (!exists("csv")) csv = 'out/campbell_omega.csv'
if (!exists("png")) png = 'campbell.png'
if (!exists("unit")) unit = 'rad/s'
if (!exists("family")) family = 'balanced'
if (!exists("critical")) critical = ''
if (!exists("omega_n")) omega_n = ''
if (!exists("title")) title = 'Campbell diagram'

set terminal pngcairo size 1100,1150 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

# A point of `family` whose mode label is `lab`, else NaN.
pick(lab, y) = (strcol("family") eq family && strcol("label") eq lab) ? y : NaN
# The signed whirl frequency in the display unit: backward whirl below the axis.
signed(v) = strcol("whirl") eq 'backward' ? -v : v

# Signed log for damping (zeta spans 1e-7 .. 1 and its sign is the point):
# S(z) = sgn(z) log10(1 + |z| / z0), z0 = 1e-8.
z0 = 1e-8
S(z) = sgn(z) * log10(1 + abs(z) / z0)

set style line 1 lc rgb '#d62728' pt 7 ps 0.6   # rotor forward whirl
set style line 2 lc rgb '#1f77b4' pt 8 ps 0.8   # rotor backward whirl (open, over the forward dots)
set style line 3 lc rgb '#7f7f7f' pt 7 ps 0.3   # ball mode
set style line 4 lc rgb '#2ca02c' pt 7 ps 0.3   # ball relative mode

stats csv using (column("speed")) nooutput
xmax = STATS_max
xmin = STATS_min
set xrange [0:xmax * 1.02]
set xlabel sprintf('speed {/Symbol w} [%s]', unit)
set grid
set key outside right top
set lmargin at screen 0.10
set rmargin at screen 0.72
set multiplot layout 3,1 title sprintf('%s: %s state', title, family) noenhanced

# Vertical markers: omega_n (dotted grey) and the critical speeds (dashed black).
if (omega_n ne '') set arrow 1 from first (omega_n + 0), graph 0 to first (omega_n + 0), graph 1 nohead lc rgb '#888888' dt 3
if (omega_n ne '') set label 1 sprintf('{/Symbol w}_n = %.4g %s', omega_n + 0, unit) at first (omega_n + 0), graph 0.96 offset 0.5,0 font ',9'
do for [i = 1:words(critical)] {
  c = word(critical, i) + 0
  set arrow (10 + i) from first c, graph 0 to first c, graph 1 nohead lc rgb 'black' dt (8,4) lw 1.2
  set label (10 + i) sprintf('critical %.5g %s', c, unit) at first c, graph (0.86 - 0.07 * (i - 1)) offset 0.5,0 font ',9'
}

set ylabel sprintf('whirl frequency {/Symbol W} [%s], fixed frame', unit)
stats csv using (pick('rotor backward whirl', column("whirl_display"))) nooutput
ybw = (STATS_records > 0 && STATS_max == STATS_max) ? STATS_max : 0
set yrange [-(ybw * 1.6 + xmax * 0.05):xmax * 1.15]
set arrow 3 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  x with lines lc rgb 'black' lw 1 dt 1 title '1X ({/Symbol W} = {/Symbol w})', \
  csv using (column("speed")):(pick('ball mode', signed(column("whirl_display")))) with points ls 3 title 'ball mode (balls together)', \
  csv using (column("speed")):(pick('ball relative mode', signed(column("whirl_display")))) with points ls 4 title 'ball relative mode', \
  csv using (column("speed")):(pick('rotor forward whirl', signed(column("whirl_display")))) with points ls 1 title 'rotor forward whirl ({/Symbol W} > 0)', \
  csv using (column("speed")):(pick('rotor backward whirl', signed(column("whirl_display")))) with points ls 2 title 'rotor backward whirl ({/Symbol W} < 0)'
set autoscale y
unset arrow 3
unset label 1
do for [i = 1:words(critical)] { unset label (10 + i) }

set ylabel 'damping ratio {/Symbol z}   sgn log_{10}(1 + |{/Symbol z}|/10^{-8})'
set ytics ('0' 0)
do for [e = -6:0:2] {
  set ytics add (sprintf('10^{%d}', e) S(10.0**e), sprintf('-10^{%d}', e) S(-(10.0**e)))
}
set arrow 2 from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#555555' dt 3
plot \
  csv using (column("speed")):(pick('rotor forward whirl', S(column("zeta")))) with points ls 1 title 'rotor forward whirl ({/Symbol W} > 0)', \
  csv using (column("speed")):(pick('rotor backward whirl', S(column("zeta")))) with points ls 2 title 'rotor backward whirl', \
  csv using (column("speed")):(pick('ball mode', S(column("zeta")))) with points ls 3 title 'ball mode', \
  csv using (column("speed")):(pick('ball relative mode', S(column("zeta")))) with points ls 4 title 'ball relative mode'

set ylabel 'log decrement {/Symbol d}   sgn log_{10}(1 + |{/Symbol d}|/10^{-8})'
set ytics ('0' 0)
do for [e = -6:4:2] {
  set ytics add (sprintf('10^{%d}', e) S(10.0**e), sprintf('-10^{%d}', e) S(-(10.0**e)))
}
plot \
  csv using (column("speed")):(pick('rotor forward whirl', S(column("log_decrement")))) with points ls 1 title 'rotor forward whirl ({/Symbol W} > 0)', \
  csv using (column("speed")):(pick('rotor backward whirl', S(column("log_decrement")))) with points ls 2 title 'rotor backward whirl', \
  csv using (column("speed")):(pick('ball mode', S(column("log_decrement")))) with points ls 3 title 'ball mode', \
  csv using (column("speed")):(pick('ball relative mode', S(column("log_decrement")))) with points ls 4 title 'ball relative mode'
unset multiplot
