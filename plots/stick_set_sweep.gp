# A sweep of a coulomb-set scene (model.md §14), two panels against the swept parameter:
#   top:    V (worst |q| over the part of the stick set connected to a balanced point),
#           V_E (worst |q| over the whole set) and the rotor without balls, on a log axis;
#   bottom: the stick set's area [rad^n].
# Reads sweep_stick_NAME.csv of `stability-scan sweep` on a coulomb-set scene; re-run by hand with
#   gnuplot -e "csv='out/sweep_stick_omega.csv'; png='x.png'; param='omega'; unit='rad/s'; logx='0'; title='x'; nballs='2'" plots/stick_set_sweep.gp
# Columns by header name: <param>, worst_q_abs (empty where no balanced point is in the
# set), worst_q_abs_any, bare_rotor_q_abs, area.
if (!exists("csv")) csv = 'out/sweep_stick_omega.csv'
if (!exists("png")) png = 'sweep_stick_omega.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = ''
if (!exists("subtitle")) subtitle = ''
if (!exists("nballs")) nballs = 'n'
# What V is connected to: balance, or on an unround race its least-|q| stable equilibrium (model.md §20.5).
if (!exists("anchor")) anchor = 'balance'

set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
header_of(f) = system(sprintf("grep -m1 -v '^#' '%s' | tr ',\\r' '  '", f))
COL = "H = header_of(csv); c = 0; do for [i = 1 : words(H)] { if (word(H, i) eq name) { c = i } }; " . \
      "if (c == 0) { print sprintf('stick_set_sweep.gp: %s has no column %s', csv, name); exit status 1 }"
name = param; eval COL; c_p = c
name = 'worst_q_abs'; eval COL; c_v = c
name = 'worst_q_abs_any'; eval COL; c_ve = c
name = 'bare_rotor_q_abs'; eval COL; c_b = c
name = 'area'; eval COL; c_a = c
V(c) = strlen(strcol(c)) == 0 ? NaN : column(c)

set terminal pngcairo size 1000,860 enhanced font 'DejaVu Sans,10'
set output png
# The subtitle's lines are separated by '|'.
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set multiplot layout 2,1 title heading noenhanced
if (logx eq '1') { set logscale x }
set grid
set tics out
set autoscale xfix
if (logx eq '1') { set format x '%g' }
set lmargin 12
set key top left box opaque
set logscale y
set format y '10^{%L}'
set ylabel '|q| [m] (rotating frame = fixed-frame whirl radius)'
set xlabel ''
plot csv using (column(c_p)):(V(c_v)) with linespoints lw 2 pt 7 ps 0.6 lc rgb '#1565c0' title 'V: worst |q| connected to '.anchor, \
     csv using (column(c_p)):(V(c_ve)) with linespoints lw 1.5 pt 5 ps 0.5 dt 2 lc rgb '#c62828' title 'V_E: worst |q| over the whole set', \
     csv using (column(c_p)):(V(c_b)) with lines lw 1.5 lc rgb '#444444' dt 4 title 'rotor without balls'
unset logscale y
set format y '%g'
set ylabel sprintf('area of the stick set [rad^%s]', nballs)
set xlabel sprintf('%s [%s]', param, unit) noenhanced
set key off
plot csv using (column(c_p)):(column(c_a)) with linespoints lw 2 pt 7 ps 0.6 lc rgb '#2e7d32'
unset multiplot
