# Sweep chart for an unround race on an anisotropic support (docs/model.md §20.6): above, each
# periodic orbit's max |q| over the period (and its min |q|, thin) against the swept parameter,
# stable filled, unstable open; below, its largest Floquet multiplier modulus max|rho| over
# pi/omega with the unit circle |rho| = 1 dashed and the located crossings (fold +1, flip -1,
# Neimark-Sacker complex) marked and labelled. Reads sweep_NAME.csv and floquet_crossings_NAME.csv
# written by `stability-scan sweep` on such a scene; re-run with
#   gnuplot -e "csv='out/sweep_omega.csv'; crossings='out/floquet_crossings_omega.csv'; png='x.png'; param='omega'; unit='rad/s'; logx='0'; title='x'; has_crossings='1'" plots/sweep_composed.gp
if (!exists("csv")) csv = 'out/sweep_omega.csv'
if (!exists("crossings")) crossings = 'out/floquet_crossings_omega.csv'
if (!exists("png")) png = 'sweep_composed.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("logx")) logx = '0'
if (!exists("title")) title = 'sweep'
if (!exists("subtitle")) subtitle = ''
if (!exists("has_crossings")) has_crossings = '1'  # the caller says whether the crossings file has rows

set terminal pngcairo size 1250,900 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''
if (logx eq '1') set logscale x
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
st(col, want) = (strcol("stability") eq want) ? column(col) : NaN
kindlabel(k) = k eq 'fold' ? 'fold (+1)' : k eq 'flip' ? 'flip (-1)' : 'N-S (complex)'

set multiplot layout 2,1 title heading noenhanced font ',9'
set lmargin at screen 0.09  # one x axis for both panels, whatever the keys' widths
set rmargin at screen 0.82
set grid
set key outside right top
set format x ''
set xlabel ''
set ylabel '|q| over the period [m]'
set format y '%.2e'
plot csv using (column(param)):(st("q_abs_max", 'stable')) with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'max |q|, stable', \
     csv using (column(param)):(st("q_abs_max", 'unstable')) with points pt 6 ps 0.9 lc rgb '#d62728' title 'max |q|, unstable', \
     csv using (column(param)):(st("q_abs_min", 'stable')) with points pt 1 ps 0.6 lc rgb '#1f77b4' title 'min |q|, stable', \
     csv using (column(param)):(st("q_abs_min", 'unstable')) with points pt 1 ps 0.6 lc rgb '#d62728' title 'min |q|, unstable'
set format x '% g'
set format y '% g'
set xlabel sprintf('%s [%s]', param, unit) noenhanced
set ylabel 'largest Floquet multiplier modulus max|{/Symbol r}| over {/Symbol p}/{/Symbol w}'
base = "1 with lines dt (8,6) lw 1.5 lc rgb '#555555' title '|{/Symbol r}| = 1', " . \
  "csv using (column(param)):(st(\"rho_abs_max\", 'stable')) with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'stable', " . \
  "csv using (column(param)):(st(\"rho_abs_max\", 'unstable')) with points pt 6 ps 0.9 lc rgb '#d62728' title 'unstable', " . \
  "csv using (column(param)):(st(\"rho_abs_max\", 'marginal')) with points pt 4 ps 0.9 lc rgb '#ff7f0e' title 'marginal'"
marks = "crossings using 2:(1):(kindlabel(strcol(\"kind\"))) with labels rotate by 90 left point pt 2 ps 2.5 lw 2 lc rgb '#2ca02c' offset 0,1 noenhanced title 'crossing (bisection)'"
if (has_crossings eq '1') { eval('plot ' . base . ', ' . marks) } else { eval('plot ' . base) }
unset multiplot
