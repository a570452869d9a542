# Branches of an unround race's equilibria in the unroundness factor (model.md §11.10):
# the residual whirl |q| against the factor e (every race amplitude times e), stable solid
# and thick, unstable dashed; folds LP, branch points BP and Hopf points HB marked. Re-run with
#   gnuplot -e "branches='out/branch_unroundness.csv'; specials='out/special_unroundness.csv'; png='b.png'; title='x'" plots/unround_branches.gp
if (!exists("branches")) branches = 'out/branch_unroundness.csv'
if (!exists("specials")) specials = 'out/special_unroundness.csv'
if (!exists("png")) png = 'branch_unroundness.png'
if (!exists("title")) title = 'unround race: continuation in the unroundness'
if (!exists("subtitle")) subtitle = ''

set terminal pngcairo size 1000,700 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
set title heading noenhanced font ',9'
set xlabel 'unroundness factor e (every race amplitude times e; 1 = the scene)'
set ylabel 'residual whirl |q| [m] (fixed frame)'
set logscale y
set format y '10^{%T}'
set grid
set key outside right top
set rmargin at screen 0.72
stats branches using (column("branch")) nooutput
nb = int(STATS_max)
# |q| -> 0 at a round race's balanced state (e = 0): the axis spans 4 decades below the largest |q|.
stats branches using (column("q_abs")) nooutput
qmax = STATS_max
pick(k, s) = (column("branch") == k && column("stable") == s && column("q_abs") > 0) ? column("q_abs") : NaN
set datafile nocolumnheaders
stats specials using (1) nooutput
set datafile columnheaders
has_specials = STATS_records > 1
special(lbl) = (strcol("label") eq lbl) ? column("q_abs") : NaN
count(lbl) = (strcol("label") eq lbl) ? 1 : 0
has_lp = 0; has_hb = 0; has_bp = 0
if (has_specials) {
  stats specials using (count('LP')) nooutput
  has_lp = STATS_sum > 0
  stats specials using (count('HB')) nooutput
  has_hb = STATS_sum > 0
  stats specials using (count('BP')) nooutput
  has_bp = STATS_sum > 0
}
set yrange [qmax / 1e4 : qmax * 2]
plot for [k = 1:nb] branches using (column("unroundness")):(pick(k, 1)) with lines lw 2.5 lc k title (k == 1 ? 'stable' : ''), \
     for [k = 1:nb] branches using (column("unroundness")):(pick(k, 0)) with lines lw 1 dt (6,4) lc k title (k == 1 ? 'unstable' : ''), \
     (has_specials ? specials : 1/0) using (column("unroundness")):(special('LP')) with points pt 5 ps 1.2 lc rgb 'black' title (has_lp ? 'LP (fold)' : ''), \
     (has_specials ? specials : 1/0) using (column("unroundness")):(special('HB')) with points pt 9 ps 1.4 lc rgb 'red' title (has_hb ? 'HB (stability lost/gained, complex pair)' : ''), \
     (has_specials ? specials : 1/0) using (column("unroundness")):(special('BP')) with points pt 13 ps 1.2 lc rgb 'blue' title (has_bp ? 'BP (branch point)' : '')
