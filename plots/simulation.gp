# Simulation chart (model.md §15): |q| and omega against t (top), the ball angles against t
# (bottom left, as points since they wrap: relative to the nearest balanced configuration when one exists, else wrapped
# to [-pi, pi]; with stick='1' (coulomb-set, model.md §14.5) the samples where a ball sticks are ringed), and the rotor centre's orbit in the FIXED frame (bottom right).
# Reads simulation.csv written by `stability-scan simulate`, columns by header name; re-run by hand with
#   gnuplot -e "csv='out/simulate/simulation.csv'; png='sim.png'; n='2'; rel='1'; omega_n='249.9'; title='x'" plots/simulation.gp
if (!exists("csv")) csv = 'out/simulate/simulation.csv'
if (!exists("png")) png = 'simulation.png'
if (!exists("n")) n = '2'
if (!exists("rel")) rel = '1'
if (!exists("omega_n")) omega_n = '0'
if (!exists("title")) title = 'simulation'
if (!exists("stick")) stick = '0'
nb = int(n)
wn = real(omega_n)

set terminal pngcairo size 1400,1000 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''
set multiplot title title noenhanced
set grid

# --- top: |q| (left axis) and omega (right axis) against t
set origin 0.0, 0.5
set size 1.0, 0.47
set xlabel 't [s]'
set ylabel '|q| [m] (rotating frame = fixed-frame whirl radius)'
set y2label 'omega [rad/s]'
set ytics nomirror
set y2tics
set key top left
# The omega_n line only where there is one (a flexible shaft has none, model.md §18.16): a key
# entry without its line would name nothing.
natural = (wn > 0 ? ", wn axes x1y2 with lines lw 1 lc rgb '#999999' title 'omega_n'" : "")
plot csv using (column("t")):(column("q_abs")) with lines lw 1.5 lc rgb '#1f77b4' title '|q|', \
     csv using (column("t")):(column("omega")) axes x1y2 with lines lw 1.5 dt (6,4) lc rgb '#d62728' title 'omega' @natural
unset y2tics
unset y2label
set ytics mirror

# --- bottom left: ball angles against t
set origin 0.0, 0.0
set size 0.55, 0.5
set ylabel (rel eq '1' ? 'beta_i - beta_i(balanced) [rad]' : 'beta_i wrapped to [-pi, pi] [rad]') noenhanced
set key top right
wrap(x) = atan2(sin(x), cos(x))
angle(i) = rel eq '1' ? column(sprintf("beta_rel%d", i)) : wrap(column(sprintf("beta%d", i)))
if (stick eq '1') {
  plot for [i=1:nb] csv using (column("t")):(angle(i)) with points pt 7 ps 0.25 lc i title sprintf('ball %d', i), \
       for [i=1:nb] csv using (column("t")):(column(sprintf("stick%d", i)) > 0 ? angle(i) : NaN) with points pt 6 ps 0.9 lc i title sprintf('ball %d stuck', i)
} else {
  plot for [i=1:nb] csv using (column("t")):(angle(i)) with points pt 7 ps 0.25 title sprintf('ball %d', i)
}

# --- bottom right: orbit of the rotor centre in the fixed frame
set origin 0.55, 0.0
set size 0.45, 0.5
set size ratio -1
set xlabel 'x fixed [m]'
set ylabel 'y fixed [m]'
set format x '%.1e'
set format y '%.1e'
set xtics rotate by 30 right
unset key
plot csv using (column("x_fixed")):(column("y_fixed")) with lines lw 0.8 lc rgb '#2ca02c'
unset multiplot
