# Stability map of a flexible rotor's balanced state (model.md §18.13): per cell the
# spectral abscissa max Re lambda [1/s] of the rightmost eigenvalues found by ARPACK (left;
# blue: stable, red: unstable, the colour scale breaks at 0; white: no balanced state or no
# eigenvalue), and the verdict (right; grey: undetermined, i.e. the search fell short or did
# not cover Re >= 0). Reads shaft_map_X_Y.csv of `stability-scan map` on a shaft scene:
#   gnuplot -e "csv='out/shaft_map_omega_bearing_k.csv'; png='m.png'; xname='omega'; yname='bearing_k'; xunit='rad/s'; yunit='N/m'; logx='0'; logy='0'; title='x'" plots/shaft_map.gp
if (!exists("csv")) csv = 'out/shaft_map_omega_bearing_k.csv'
if (!exists("png")) png = 'shaft_map.png'
if (!exists("xname")) xname = 'omega'
if (!exists("yname")) yname = 'bearing_k'
if (!exists("xunit")) xunit = 'rad/s'
if (!exists("yunit")) yunit = 'N/m'
if (!exists("logx")) logx = '0'
if (!exists("logy")) logy = '0'
if (!exists("title")) title = 'flexible shaft map'
if (!exists("subtitle")) subtitle = ''

set terminal pngcairo size 1300,600 enhanced font 'DejaVu Sans,10'
set output png
set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

heading = title
if (subtitle ne '') { heading = heading . "\n"; do for [i = 1:strlen(subtitle)] { heading = heading . (subtitle[i:i] eq '|' ? "\n" : subtitle[i:i]) } }
label(name, unit, lg) = (lg eq '1' ? 'log_{10} ' : '') . name . (unit eq '-' ? '' : ' [' . unit . ']')
X(v) = (logx eq '1' ? log10(v) : v)
Y(v) = (logy eq '1' ? log10(v) : v)
set xlabel label(xname, xunit, logx) noenhanced
set ylabel label(yname, yunit, logy) noenhanced
set multiplot layout 1,2 title heading noenhanced font ',9'
set autoscale xfix
set autoscale yfix
# The abscissa's range; the palette breaks at 0 (stable blues below, unstable reds above).
abscissa(v) = (strcol("found") eq '0' ? NaN : v)
stats csv using (abscissa(column("spectral_abscissa"))) nooutput
lo = STATS_min
hi = STATS_max
if (hi <= 0) {
  set palette defined (0 '#08306b', 1 '#c6dbef')
} else { if (lo >= 0) {
  set palette defined (0 '#fcbba1', 1 '#67000d')
} else {
  z = -lo / (hi - lo)
  set palette defined (0 '#08306b', z * 0.999 '#c6dbef', z '#fcbba1', 1 '#67000d')
} }
if (hi > lo) { set cbrange [lo:hi] }
set cblabel 'spectral abscissa max Re {/Symbol l} [1/s] (rotating frame)'
set title 'spectral abscissa (blue < 0 < red)'
plot csv using (X(column(xname))):(Y(column(yname))):(abscissa(column("spectral_abscissa"))) with image notitle
set autoscale cb
unset colorbox
set cbrange [0:3]
set palette defined (0 '#2166ac', 1 '#2166ac', 1 '#b2182b', 2 '#b2182b', 2 '#999999', 3 '#999999')
verdict(s) = (s eq 'stable' ? 0.5 : s eq 'unstable' ? 1.5 : s eq 'undetermined' ? 2.5 : NaN)
set title 'verdict: blue stable, red unstable, grey undetermined, white no balanced state'
plot csv using (X(column(xname))):(Y(column(yname))):(verdict(strcol("verdict"))) with image notitle
unset multiplot
