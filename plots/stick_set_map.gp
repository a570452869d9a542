# Heat maps of a stick-set map of coulomb-set friction (model.md §14), two PNGs:
#   png_worst: V, the worst residual vibration |q| [m] over the part of the stick set
#              connected to a balanced point, on a log colour scale (grey: no balanced
#              point in the set, V not defined);
#   png_area:  the stick set's area as a fraction of the torus (0: no arrangement sticks,
#              1: every arrangement sticks).
# Reads summary_X_Y.csv of `stability-scan map` on a coulomb-set scene; re-run by hand with
#   gnuplot -e "summary='out/stick_map/summary_omega_mu.csv'; png_worst='v.png'; png_area='a.png'; xname='omega'; xunit='rad/s'; yname='mu'; yunit='-'; logx='0'; logy='1'; title='x'" plots/stick_set_map.gp
# Columns are found by their header name: <xname>, <yname>, worst_q_abs (empty where not
# defined), area_fraction. A log axis is drawn as log10 of the value (cells are evenly
# spaced there, as `with image` needs).
if (!exists("summary")) summary = 'out/stick_map/summary_omega_mu.csv'
if (!exists("png_worst")) png_worst = 'stick_worst.png'
if (!exists("png_area")) png_area = 'stick_area.png'
if (!exists("xname")) xname = 'omega'
if (!exists("xunit")) xunit = 'rad/s'
if (!exists("yname")) yname = 'mu'
if (!exists("yunit")) yunit = '-'
if (!exists("logx")) logx = '0'
if (!exists("logy")) logy = '0'
if (!exists("title")) title = ''

set datafile separator ','
set datafile commentschars '#'
set datafile columnheaders
header_of(f) = system(sprintf("grep -m1 -v '^#' '%s' | tr ',\\r' '  '", f))
COL = "H = header_of(summary); c = 0; do for [i = 1 : words(H)] { if (word(H, i) eq name) { c = i } }; " . \
      "if (c == 0) { print sprintf('stick_set_map.gp: %s has no column %s', summary, name); exit status 1 }"
name = xname; eval COL; c_x = c
name = yname; eval COL; c_y = c
name = 'worst_q_abs'; eval COL; c_v = c
name = 'area_fraction'; eval COL; c_a = c

lx = (logx eq '1'); ly = (logy eq '1')
X(v) = lx ? log10(v) : v
Y(v) = ly ? log10(v) : v
xlabel = lx ? sprintf('log10(%s) [%s]', xname, xunit) : sprintf('%s [%s]', xname, xunit)
ylabel = ly ? sprintf('log10(%s) [%s]', yname, yunit) : sprintf('%s [%s]', yname, yunit)

set terminal pngcairo size 960,720 enhanced font 'DejaVu Sans,10'
set xlabel xlabel noenhanced
set ylabel ylabel noenhanced
set key off
set tics out
set autoscale xfix
set autoscale yfix
set rmargin at screen 0.80

# ---- V on a log colour scale; grey where no balanced point is in the set ----
stats summary using (column(c_v)) nooutput
have_v = (STATS_records > 0)
set output png_worst
set title sprintf("worst residual vibration V over the stick set (coulomb-set, model.md §14; |q| in the rotating frame = whirl radius)\n%s", title) noenhanced
set cblabel 'V = max |q| connected to balance [m]'
set palette defined (0 '#313695', 0.25 '#74add1', 0.5 '#ffffbf', 0.75 '#f46d43', 1 '#a50026')
# a log colour scale when V spans more than a decade (its tics are decades), else linear
set format cb '%.1e'
if (have_v) {
  set cbrange [STATS_min:STATS_max]
  if (STATS_min == STATS_max) { set cbrange [STATS_min*0.9:STATS_max*1.1] }
  if (STATS_min > 0 && STATS_max > 10 * STATS_min) { set logscale cb; set format cb '10^{%L}' }
}
plot summary using (X(column(c_x))):(Y(column(c_y))):(strlen(strcol(c_v)) == 0 ? 1 : NaN) with image lc rgb '#a6a6a6', \
     summary using (X(column(c_x))):(Y(column(c_y))):(strlen(strcol(c_v)) == 0 ? NaN : column(c_v)) with image

# ---- the area fraction ----
set output png_area
unset logscale cb
set format cb '%g'
set cbrange [0:1]
set cblabel 'area of the stick set / (2 pi)^n'
set palette defined (0 '#ffffff', 1 '#1b7837')
set title sprintf("area of the stick set, fraction of the torus (coulomb-set, model.md §14)\n%s", title) noenhanced
plot summary using (X(column(c_x))):(Y(column(c_y))):(column(c_a)) with image
