# Continuation chart for an unround race on an anisotropic support (docs/model.md §20.9): above,
# each branch of periodic orbits as a line of max |q| over the period against the parameter,
# stable blue, unstable red, marginal orange, through its folds; below, its largest Floquet
# multiplier modulus max|rho| over pi/omega with |rho| = 1 dashed. The located special points
# (LP fold, BP, PD flip, NS Neimark-Sacker) are marked and labelled on both. Reads
# branch_NAME.csv and special_NAME.csv written by `stability-scan continue` on such a scene;
# re-run with
#   gnuplot -e "csv='out/branch_omega.csv'; specials='out/special_omega.csv'; png='x.png'; param='omega'; unit='rad/s'; title='x'; has_specials='1'" plots/continue_composed.gp
if (!exists("csv")) csv = 'out/branch_omega.csv'
if (!exists("specials")) specials = 'out/special_omega.csv'
if (!exists("png")) png = 'continue_composed.png'
if (!exists("param")) param = 'omega'
if (!exists("unit")) unit = 'rad/s'
if (!exists("title")) title = 'continuation'
if (!exists("subtitle")) subtitle = ''
if (!exists("has_specials")) has_specials = '1'  # the caller says whether the specials file has rows

set terminal pngcairo size 1250,900 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''
heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
colour(s) = s eq 'stable' ? 0x1f77b4 : s eq 'unstable' ? 0xd62728 : 0xff7f0e

set multiplot layout 2,1 title heading noenhanced font ',9'
set lmargin at screen 0.09  # one x axis for both panels, whatever the keys' widths
set rmargin at screen 0.82
set grid
set key outside right top
set format x ''
set xlabel ''
set ylabel '|q| over the period [m]'
set format y '%.2e'
# dummy entries for the key: the colours of the line segments
key = "NaN with lines lw 2.5 lc rgb '#1f77b4' title 'stable', NaN with lines lw 2.5 lc rgb '#d62728' title 'unstable', " . \
      "NaN with lines lw 2.5 lc rgb '#ff7f0e' title 'marginal'"
lines_q = "csv using (column(param)):(column('q_abs_max')):(colour(strcol('stability'))) with lines lw 2.5 lc rgb variable notitle"
marks_q = "specials using (column(param)):(column('q_abs_max')):(strcol('kind')) with labels left offset 0.6,0.6 point pt 6 ps 1.6 lw 2 lc rgb '#2ca02c' noenhanced title 'special point'"
if (has_specials eq '1') { eval('plot ' . lines_q . ', ' . key . ', ' . marks_q) } else { eval('plot ' . lines_q . ', ' . key) }
set format x '% g'
set format y '% g'
set xlabel sprintf('%s [%s]', param, unit) noenhanced
set ylabel 'largest Floquet multiplier modulus max|{/Symbol r}| over {/Symbol p}/{/Symbol w}'
lines_r = "csv using (column(param)):(column('rho_abs_max')):(colour(strcol('stability'))) with lines lw 2.5 lc rgb variable notitle"
unit_circle = "1 with lines dt (8,6) lw 1.5 lc rgb '#555555' title '|{/Symbol r}| = 1'"
marks_r = "specials using (column(param)):(column('rho_abs_max')):(strcol('kind')) with labels left offset 0.6,0.6 point pt 6 ps 1.6 lw 2 lc rgb '#2ca02c' noenhanced notitle"
if (has_specials eq '1') { eval('plot ' . lines_r . ', ' . unit_circle . ', ' . marks_r) } else { eval('plot ' . lines_r . ', ' . unit_circle) }
unset multiplot
