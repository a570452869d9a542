# Heat maps of a two-parameter stability map, each written as PNG and SVG:
#   stability: where the balanced state (q = 0) is absent / exists but unstable / stable
#              (n-ball maps: also "partly stable", some samples of the balanced set stable);
#   vibration: the residual vibration |q| of the best stable state on a log colour scale,
#              grey where no state is stable;
#   fraction (n-ball maps, nballs='1'): balanced_stable_fraction, the fraction of the
#              balanced set's samples that are normally stable (model.md §13.5).
# The fold (LP, black) and Hopf (HB, red) curves and the codimension-two points on them
# are drawn on top of both when a boundary CSV is given. Reads the CSVs of
# `stability-scan map`; re-run by hand with
#   gnuplot -e "summary='out/map/summary_omega_mu.csv'; curves='out/map/boundary_omega_mu.csv'; png_stability='s.png'; svg_stability='s.svg'; png_vibration='v.png'; svg_vibration='v.svg'; xname='omega'; xunit='rad/s'; yname='mu'; yunit='-'; logx='0'; logy='1'; title='x'" plots/map.gp
# (curves='' when there is no boundary file; n-ball maps add nballs='1'; png_fraction='f.png';
# svg_fraction='f.svg').
# Columns are found by their header NAME (the first line that is not a comment), never
# by position: summary ix, iy, <xname>, <yname>, and two balls balanced, balanced_stable
#   (empty without a balanced state), n_stable, best_q_abs [m] (empty if nothing is
#   stable); n balls balanced_exists, balanced_stable_fraction (empty without samples),
#   n_stable, best_q_abs. Rows in order ix outer, iy inner; x and y evenly spaced (in
#   log10 on a log axis). boundary: curve, kind (LP|HB), label, <xname>, <yname>.
#
# How it is drawn:
# - Cells sit at their grid indices (ix, iy), so `with image` always sees an even grid and
#   embeds one bitmap, in the SVG too (on a gnuplot log axis it would draw a rectangle per
#   cell). The tics are put at physical values through value <-> index, linear or log10
#   (decades labelled 10^k); the boundary curves go through the same mapping.
# - A grid one cell wide in x or y is drawn as boxes; that axis has its single value as
#   its only tic, and the curves are drawn against a notional cell width of 2 % of the
#   value (log: 0.02 decade).
# - |q| colour scale: from the least |q| above 1e-15 m to the largest; a stable state with
#   |q| <= 1e-15 m (balanced: 0) gets its own colour (white), with its own key entry.
# - The SVG embeds the image as one bitmap (not a rectangle per cell); viewers may smooth
#   it when it is enlarged.
# - Speed (1000 x 1000 cells): the geometry comes from a few rows (row 0, the rows with
#   ix = 0, every ny-th row), the summary is read once per chart (the first read also finds
#   the |q| range), and each SVG is redrawn from the data already read (`refresh`).
# - `stability-scan map` itself passes the compact grid instead of the summary (grid_file =
#   a binary file of nx x ny records of three float64: category 0..3 as below, |q| of the
#   best stable state (NaN: none is stable), balanced_stable_fraction (NaN: not defined);
#   records in the summary's order, ix outer, iy inner) with the geometry and the |q|
#   range (grid_nx, grid_ny, grid_x0, grid_y0, grid_x1, grid_y1, grid_qlo, grid_qhi,
#   grid_low): no CSV is read, the same pictures.
if (!exists("summary")) summary = 'out/map/summary_omega_mu.csv'
if (!exists("curves")) curves = ''
if (!exists("png_stability")) png_stability = 'stability.png'
if (!exists("svg_stability")) svg_stability = 'stability.svg'
if (!exists("png_vibration")) png_vibration = 'vibration.png'
if (!exists("svg_vibration")) svg_vibration = 'vibration.svg'
if (!exists("xname")) xname = 'omega'
if (!exists("xunit")) xunit = 'rad/s'
if (!exists("yname")) yname = 'mu'
if (!exists("yunit")) yunit = '-'
if (!exists("logx")) logx = '0'
if (!exists("logy")) logy = '0'
if (!exists("title")) title = ''
if (!exists("nballs")) nballs = '0'
if (!exists("png_fraction")) png_fraction = 'fraction.png'
if (!exists("svg_fraction")) svg_fraction = 'fraction.svg'
if (!exists("grid_file")) grid_file = ''
nb = (nballs eq '1')
bin = (strlen(grid_file) > 0)

set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders

c_none = '#d9d9d9'      # stability chart: no balanced state
c_unstable = '#fee090'  #   balanced state exists, unstable
c_stable = '#74add1'    #   balanced state stable
c_partly = '#b8d8a0'    #   n balls: some samples of the balanced set stable
c_nostable = '#a6a6a6'  # vibration chart: no stable state
c_zero = '#ffffff'      #   a stable state with |q| = 0 (balanced)
c_hopf = '#d62728'
c_fold = '#1f1f1f'
qfloor = 1e-15          # |q| at or below this [m] counts as 0

# ---- columns by name ----------------------------------------------------------------
# `name = 'x'; file = f; eval COL` sets c to the 1-based index of column x in f's header.
header_of(f) = system(sprintf("grep -m1 -v '^#' '%s' | tr ',\\r' '  '", f))
COL = "H = header_of(file); c = 0; do for [i = 1 : words(H)] { if (word(H, i) eq name) { c = i } }; " . \
      "if (c == 0) { print sprintf('map.gp: %s has no column %s', file, name); exit status 1 }"
if (!bin) {
  file = summary
  name = 'ix'; eval COL; c_ix = c
  name = 'iy'; eval COL; c_iy = c
  name = xname; eval COL; c_x = c
  name = yname; eval COL; c_y = c
  name = 'n_stable'; eval COL; c_nstable = c
  name = 'best_q_abs'; eval COL; c_q = c
  if (nb) {
    name = 'balanced_exists'; eval COL; c_bal = c
    name = 'balanced_stable_fraction'; eval COL; c_balst = c
  } else {
    name = 'balanced'; eval COL; c_bal = c
    name = 'balanced_stable'; eval COL; c_balst = c
  }
}

# ---- grid geometry -------------------------------------------------------------------
if (bin) {
  nx = int(grid_nx + 0)
  ny = int(grid_ny + 0)
  x0 = grid_x0 + 0
  y0 = grid_y0 + 0
  x1 = grid_x1 + 0
  y1 = grid_y1 + 0
} else {
  K = 256
  more = 1
  while (more) {
    stats summary every ::0::(K-1) using (column(c_ix)) nooutput
    more = (STATS_max == 0 && STATS_records == K)
    if (more) { K = 2 * K }
  }
  # the first K rows hold all rows with ix = 0: x0 y0 from iy = 0, y1 from the last of them
  stats summary every ::0::(K-1) using (column(c_ix) == 0 ? (column(c_iy) == 0 ? (x0 = column(c_x), y0 = column(c_y)) : 0, \
    y1 = column(c_y), column(c_iy)) : NaN) nooutput
  ny = int(STATS_max) + 1
  # rows iy = 0, one per ix: x1 from the last
  stats summary every ny using (x1 = column(c_x), column(c_ix)) nooutput
  nx = int(STATS_max) + 1
}
grid = (nx > 1 && ny > 1)

# index <-> value: T(value at index i) = a + i d, with T(v) = v or log10(v)
lgx = (logx eq '1')
lgy = (logy eq '1')
Tx(v) = lgx ? log10(v) : v
Ty(v) = lgy ? log10(v) : v
xa = Tx(x0)
ya = Ty(y0)
xd = nx > 1 ? (Tx(x1) - xa) / (nx - 1) : (lgx ? 0.02 : (x0 != 0 ? 0.02 * abs(x0) : 1))
yd = ny > 1 ? (Ty(y1) - ya) / (ny - 1) : (lgy ? 0.02 : (y0 != 0 ? 0.02 * abs(y0) : 1))
px(v) = (Tx(v) - xa) / xd
py(v) = (Ty(v) - ya) / yd

# ---- tics at physical values ---------------------------------------------------------
# `eval TICS` sets T to a tic list for `set Xtics (...)` from: tlo < thi, the axis ends in
# T space; lg (log axis); n (cells; 1: a single tic at v1). P(t) is the tic position: the
# index (t - ta) / td, or 10^t on the (log-scaled) colour box.
nice_f(r) = (r / 10.0**floor(log10(r)) < 1.5 ? 1 : r / 10.0**floor(log10(r)) < 3.5 ? 2 : \
             r / 10.0**floor(log10(r)) < 7.5 ? 5 : 10)
nice(r) = nice_f(r) * 10.0**floor(log10(r))
P(t) = iscb ? 10.0**t : (t - ta) / td
tic(label, t, level) = sprintf('"%s" %.17g %d, ', label, P(t), level)
TICS = "T = ''; " . \
  "if (n == 1) { T = tic(sprintf('%g', v1), ta, 0) } else { if (!lg) { " . \
    "st = nice((thi - tlo) / 5); m = (nice_f((thi - tlo) / 5) == 2) ? 4 : 5; " . \
    "do for [k = ceil(tlo / st * m - 1e-6) : floor(thi / st * m + 1e-6)] { " . \
      "T = T . ((k % m == 0) ? tic(sprintf('%g', k == 0 ? 0 : k * st / m), k * st / m, 0) : tic('', k * st / m, 1)) } " . \
  "} else { d1 = ceil(tlo - 1e-9); d2 = floor(thi + 1e-9); if (d2 > d1) { " . \
    "s = (d2 - d1 + 1 > 8) ? ceil((d2 - d1 + 1) / 8.0) : 1; " . \
    "do for [k = d1 : d2] { T = T . ((k % s == 0) ? tic(sprintf('10^{%d}', k), k, 0) : tic('', k, 1)) }; " . \
    "if (s == 1) { do for [k = d1 - 1 : d2] { do for [mm = 2 : 9] { " . \
      "t = k + log10(mm); if (t > tlo && t < thi) { T = T . tic('', t, 1) } } } } " . \
  "} else { c = 0; do for [k = floor(tlo) : ceil(thi)] { do for [mm = 1 : 9] { " . \
      "t = k + log10(mm); if ((mm == 1 || mm == 2 || mm == 5) && t > tlo - 1e-9 && t < thi + 1e-9) { c = c + 1 } } }; " . \
    "if (c >= 3) { do for [k = floor(tlo) : ceil(thi)] { do for [mm = 1 : 9] { " . \
      "t = k + log10(mm); if (t > tlo - 1e-9 && t < thi + 1e-9) { " . \
        "T = T . ((mm == 1 || mm == 2 || mm == 5) ? tic(sprintf('%g', mm * 10.0**k), t, 0) : tic('', t, 1)) } } } " . \
    "} else { st = nice((10.0**thi - 10.0**tlo) / 5); " . \
      "do for [k = ceil(10.0**tlo / st - 1e-6) : floor(10.0**thi / st + 1e-6)] { " . \
        "if (k > 0) { T = T . tic(sprintf('%g', k * st), log10(k * st), 0) } } } } } }; " . \
  "if (strlen(T) > 2) { T = T[1 : strlen(T) - 2] }"

iscb = 0
do for [ax in "x y"] {
  lg = ax eq 'x' ? lgx : lgy
  n = ax eq 'x' ? nx : ny
  ta = ax eq 'x' ? xa : ya
  td = ax eq 'x' ? xd : yd
  v1 = ax eq 'x' ? x0 : y0
  te1 = ta - 0.5 * td
  te2 = ta + (n - 0.5) * td
  tlo = te1 < te2 ? te1 : te2
  thi = te1 < te2 ? te2 : te1
  eval TICS
  eval sprintf('set %stics (%s)', ax, T)
}
set tics out nomirror front
set xlabel (strlen(xunit) > 0 ? sprintf('%s [%s]', xname, xunit) : xname) noenhanced
set ylabel (strlen(yunit) > 0 ? sprintf('%s [%s]', yname, yunit) : yname) noenhanced
set lmargin at screen 0.095
set rmargin at screen 0.66
set bmargin at screen 0.09
set tmargin at screen 0.90
set key at screen 0.68, screen 0.90 left top Left reverse samplen 2 spacing 1.2
set border front
set clip two   # draw a curve segment even when both its ends lie outside the map

# ---- boundary curves -----------------------------------------------------------------
# One plot element per (curve, kind) -- the kinds and ids come from one pass over the
# file -- with a white halo under each line, then one per codimension-two label present.
CURVES = ''
if (strlen(curves) > 0) {
  set datafile nocolumnheaders
  undefine STATS_*
  stats curves using (1) nooutput   # counts the header line too: no warning for 0 rows
  set datafile columnheaders
  if (exists("STATS_records") && STATS_records > 1) {
    file = curves
    name = 'curve'; eval COL; cb_curve = c
    name = 'kind'; eval COL; cb_kind = c
    name = 'label'; eval COL; cb_label = c
    name = xname; eval COL; cb_x = c
    name = yname; eval COL; cb_y = c
    seen = ''
    labs = ' '
    lastk = NaN
    lastkind = ''
    stats curves using (k = column(cb_curve), kd = strcol(cb_kind), \
      (k != lastk || kd ne lastkind) ? (lastk = k, lastkind = kd, \
        (kd eq 'HB' || kd eq 'LP') ? (seen = seen . sprintf(' %s:%d', kd, k), 0) : 0) : 0, \
      l = strcol(cb_label), (strlen(l) > 0 && l ne 'EP' && strstrt(labs, ' ' . l . ' ') == 0) ? (labs = labs . l . ' ', 0) : 0, \
      1) nooutput
    halo = ''
    lines = ''
    hopf_titled = 0
    fold_titled = 0
    do for [w in seen] {
      kd = w[1:2]
      k = int(w[4:])
      sel = sprintf("(px(column(cb_x))):(column(cb_curve) == %d && strcol(cb_kind) eq '%s' ? py(column(cb_y)) : NaN)", k, kd)
      halo = halo . sprintf(", curves using %s with lines lw 5 lc rgb 'white' notitle", sel)
      ttl = ''
      if (kd eq 'HB' && !hopf_titled) { ttl = 'Hopf curve (HB)'; hopf_titled = 1 }
      if (kd eq 'LP' && !fold_titled) { ttl = 'fold curve (LP)'; fold_titled = 1 }
      lines = lines . sprintf(", curves using %s with lines lw 2.5 lc rgb '%s' title '%s'", \
                              sel, kd eq 'HB' ? c_hopf : c_fold, ttl)
    }
    points = ''
    do for [l in labs] {
      pt = 3; pc = '#000000'; desc = l
      if (l eq 'BT') { pt = 5; pc = '#9467bd'; desc = 'BT Bogdanov-Takens' }
      if (l eq 'ZH') { pt = 9; pc = '#ff7f0e'; desc = 'ZH zero-Hopf' }
      if (l eq 'CP') { pt = 7; pc = '#2ca02c'; desc = 'CP cusp' }
      if (l eq 'GH') { pt = 13; pc = '#17becf'; desc = 'GH generalized Hopf' }
      points = points . sprintf(", curves using (px(column(cb_x))):(strcol(cb_label) eq '%s' ? py(column(cb_y)) : NaN) " . \
                                "with points pt %d ps 1.5 lc rgb '%s' title '%s'", l, pt, pc, desc)
    }
    CURVES = halo . lines . points
  }
}

# values increase to the right and upwards even if the grid runs the other way
if (xd > 0) { set xrange [-0.5 : nx - 0.5] } else { set xrange [nx - 0.5 : -0.5] }
if (yd > 0) { set yrange [-0.5 : ny - 0.5] } else { set yrange [ny - 0.5 : -0.5] }

# ---- chart 1: stability of the balanced state ----------------------------------------
# The pass also finds the range of |q| for chart 2: qlo, qhi over |q| > qfloor; low = 1
# if a stable state has |q| <= qfloor. (The per-row work is done in functions that assign
# only when a value changes: measurably faster than assignments in the `using` spec.)
qlo = 1e300
qhi = 0
low = 0
# category: 0 no balanced state, 1 exists but unstable, 2 partly stable (n balls: some
# samples of the set), 3 stable (two balls: balanced_stable = 1; n balls: every sample)
category(balanced, stable) = balanced == 0 ? 0 : nb ? (stable == 1 ? 3 : stable > 0 ? 2 : 1) : (stable == 1 ? 3 : 1)
scan(q) = q > qfloor ? (q < qlo ? qlo = q : 0, q > qhi ? qhi = q : 0) : (q <= qfloor && !low ? low = 1 : 0)
vibration(n_stable, q) = n_stable > 0 && q > qfloor ? (q < cbmin ? cbmin : q) : NaN
# a stable state with |q| = 0 (balanced): its own colour, drawn over the colour scale
zero(n_stable, q) = n_stable > 0 && q <= qfloor
SRC = 'summary'
if (bin) {
  # the grid's records, the pixel values themselves (an expression per pixel would cost
  # gnuplot more than the drawing): 1 category; 2 |q| where a state with |q| > qfloor is
  # stable, else NaN; 3 balanced_stable_fraction (NaN: not defined); 4 255 where a state
  # with |q| <= qfloor is stable, else 0 (the white overlay: r = g = b = alpha)
  if (!grid) { print 'map.gp: grid_file needs a grid of nx > 1 and ny > 1 cells'; exit status 1 }
  qlo = grid_qlo + 0
  qhi = grid_qhi + 0
  low = int(grid_low + 0)
  SRC = sprintf("grid_file binary array=(%d,%d) scan=yx format='%%4double'", nx, ny)
  USE1 = '1'
  USE2 = '2'
  USE3 = '3'
  WITH = 'with image'
  ZERO = SRC . " using 4:4:4:4 with rgbalpha notitle"
} else {
VAL1 = sprintf('(scan(column(%d)) + category(column(%d), column(%d)))', c_q, c_bal, c_balst)
VAL2 = sprintf('(vibration(column(%d), column(%d)))', c_nstable, c_q)
VAL3 = sprintf('(column(%d) == 0 ? NaN : column(%d))', c_bal, c_balst)
if (grid) {
  USE1 = sprintf('%d:%d:', c_ix, c_iy) . VAL1
  USE2 = sprintf('%d:%d:', c_ix, c_iy) . VAL2
  USE3 = sprintf('%d:%d:', c_ix, c_iy) . VAL3
  WITH = 'with image'
  ZERO = sprintf("summary using %d:%d:(255):(255):(255):(zero(column(%d), column(%d)) ? 255 : 0) with rgbalpha notitle", \
                 c_ix, c_iy, c_nstable, c_q)
} else {
  USE1 = sprintf('%d:%d:(0.5):(0.5):', c_ix, c_iy) . VAL1
  USE2 = sprintf('%d:(column(%d) > 0 ? column(%d) : NaN):(0.5):(0.5):', c_ix, c_nstable, c_iy) . VAL2   # no box where nothing is stable
  USE3 = sprintf('%d:%d:(0.5):(0.5):', c_ix, c_iy) . VAL3
  WITH = 'with boxxyerror lc palette fs solid 1.0 border'     # border: no seams between boxes
  ZERO = sprintf("summary using %d:(zero(column(%d), column(%d)) ? column(%d) : NaN):(0.5):(0.5) " . \
                 "with boxxyerror lc rgb c_zero fs solid 1.0 border notitle", c_ix, c_nstable, c_q, c_iy)
}
}
# SVG viewers smooth an enlarged bitmap: browsers and Inkscape honour this mark
heading(what) = strlen(title) > 0 ? sprintf("%s\n%s", what, title) : what

set terminal pngcairo size 1200,800 enhanced font 'DejaVu Sans,10'
set output png_stability
set title heading('stability region of the balanced state') noenhanced
set palette defined (0 c_none, 1 c_unstable, 2 c_partly, 3 c_stable)
set cbrange [0:3]
unset colorbox
PARTLY = nb ? ", keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_partly title 'balanced set partly stable'" : ''
plot @SRC using @USE1 @WITH notitle, \
     keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_none title 'no balanced state', \
     keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_unstable title 'balanced exists, unstable' \
     @PARTLY, \
     keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_stable title 'balanced stable' \
     @CURVES
set terminal svg size 1200,800 enhanced font 'DejaVu Sans,13' background rgb 'white'
set output svg_stability
refresh
unset output

# ---- chart 2: residual vibration of the best stable state ----------------------------
if (qhi > 0) {
  cbmin = qlo
  cbmax = qhi
} else {
  cbmin = low ? qfloor : 1e-12   # nothing above qfloor: any range will do
  cbmax = low ? 10 * qfloor : 1e-3
}
if (cbmin == cbmax) { cbmin = cbmin / sqrt(10); cbmax = cbmax * sqrt(10) }
iscb = 1
lg = 1
n = 2
tlo = log10(cbmin)
thi = log10(cbmax)
eval TICS
eval sprintf('set cbtics (%s)', T)
set logscale cb
set cbrange [cbmin:cbmax]
set cblabel '|q| of the best stable state [m]' noenhanced
set colorbox user origin screen 0.675, screen 0.09 size screen 0.02, screen 0.81
set key at screen 0.77, screen 0.90
set palette defined (0 '#440154', 0.13 '#482878', 0.25 '#3e4989', 0.38 '#31688e', 0.5 '#26828e', \
                     0.63 '#1f9e89', 0.75 '#35b779', 0.88 '#6ece58', 1 '#fde725')
set object 1 rectangle from graph 0, 0 to graph 1, 1 behind fc rgb c_nostable fs solid 1.0 noborder
nostable_title = (qhi > 0 || low) ? 'no stable state' : 'no stable state (no cell has one)'
low_title = low ? 'balanced: |q| = 0' : ''
set terminal pngcairo size 1200,800 enhanced font 'DejaVu Sans,10'
set output png_vibration
set title heading('residual vibration of the best stable state') noenhanced
plot @SRC using @USE2 @WITH notitle, \
     @ZERO, \
     keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_nostable title nostable_title, \
     keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_zero title low_title \
     @CURVES
set terminal svg size 1200,800 enhanced font 'DejaVu Sans,13' background rgb 'white'
set output svg_vibration
refresh
unset output

# ---- chart 3 (n balls): fraction of the balanced set normally stable ------------------
if (nb) {
  unset logscale cb
  set cbrange [0:1]
  set cbtics 0.2
  set cblabel 'balanced_stable_fraction: samples of the balanced set normally stable' noenhanced
  set palette defined (0 c_unstable, 0.5 '#fdae61', 1 c_stable)
  set object 1 rectangle from graph 0, 0 to graph 1, 1 behind fc rgb c_none fs solid 1.0 noborder
  set terminal pngcairo size 1200,800 enhanced font 'DejaVu Sans,10'
  set output png_fraction
  set title heading('fraction of the balanced set that is stable') noenhanced
  plot @SRC using @USE3 @WITH notitle, \
       keyentry with boxes fs solid 1.0 border lc rgb '#606060' fc rgb c_none title 'no balanced state' \
       @CURVES
  set terminal svg size 1200,800 enhanced font 'DejaVu Sans,13' background rgb 'white'
  set output svg_fraction
  refresh
  unset output
}
