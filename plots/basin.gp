# Classification map of `stability-scan basin`: every cell of the grid of start angles
# (beta1, beta2) coloured by what its trajectory ended in (model.md §15.5). Re-run by hand with
#   gnuplot -e "csv='out/basin/basin.csv'; png='basin.png'; labels='balanced aligned:+- stuck'; title='x'" plots/basin.gp
# labels: the classes present (space separated): the attractor, and for an equilibrium
# reached by the settle test its member, as ATTRACTOR/MEMBER (the two mirror balanced
# states of two balls are balanced/1 and balanced/2). Each kind has its colours (balanced
# greens; aligned, an unround race's equilibria and its orbits on an anisotropic support
# red/orange/purple...; periodic blue, stuck grey shaded by the end |q|, not_settled black).
# Columns by name: beta1_0, beta2_0, attractor, member. cells1, cells2: the grid; the cell
# (i, j) starting at (2 pi i / cells1, 2 pi j / cells2) is drawn as the square from there.
if (!exists("csv")) csv = 'out/basin/basin.csv'
if (!exists("png")) png = 'basin.png'
if (!exists("labels")) labels = 'balanced'
if (!exists("title")) title = ''
if (!exists("cells1")) cells1 = 8
if (!exists("cells2")) cells2 = 8
set datafile separator ','
set datafile commentschars '#'
K = words(labels)
idx(s, k) = k > K ? 0 : (word(labels, k) eq s ? k : idx(s, k + 1))
# Colour per label kind; aligned patterns take successive warm colours.
aligned_colours = '#d62728 #ff7f0e #9467bd #8c564b #e377c2 #bcbd22'
balanced_colours = '#2ca02c #98df8a #17becf #006400'
colour_of(s, a, b) = s[1:8] eq 'balanced' ? word(balanced_colours, (b % 4) + 1) : s eq 'periodic' ? '#1f77b4' : \
                     s eq 'stuck' ? '#7f7f7f' : s eq 'not_settled' ? '#000000' : word(aligned_colours, (a % 6) + 1)
palette = ''
a = 0
b = 0
do for [k = 1:K] {
  s = word(labels, k)
  palette = palette . sprintf('%s%d "%s"', k > 1 ? ', ' : '', k, colour_of(s, a, b))
  if (s[1:8] eq 'aligned:' || s[1:11] eq 'equilibrium' || s[1:5] eq 'orbit') { a = a + 1 }
  if (s[1:8] eq 'balanced') { b = b + 1 }
}
if (K == 1) { palette = palette . sprintf(', 2 "%s"', colour_of(word(labels, 1), 0, 0)) }
eval('set palette defined (' . palette . ') maxcolors ' . (K > 1 ? K : 2))
set cbrange [0.5 : (K > 1 ? K : 2) + 0.5]
set cbtics ()
do for [k = 1:K] { eval(sprintf('set cbtics add ("%s" %d)', word(labels, k), k)) }
set terminal pngcairo size 900, 760 font ',10'
set termoption noenhanced
set output png
set title title noenhanced
set xlabel 'start angle of ball 1, beta1 [rad]'
set ylabel 'start angle of ball 2, beta2 [rad]'
set xrange [0 : 2 * pi]
set yrange [0 : 2 * pi]
set size ratio -1
set xtics ('0' 0, 'pi/2' pi / 2, 'pi' pi, '3pi/2' 3 * pi / 2, '2pi' 2 * pi)
set ytics ('0' 0, 'pi/2' pi / 2, 'pi' pi, '3pi/2' 3 * pi / 2, '2pi' 2 * pi)
# `with image` centres a pixel on its point: the cell starting at beta is drawn at its
# centre, beta + half a cell.
h1 = pi / cells1
h2 = pi / cells2
class(a, m) = m eq '' ? a : a . '/' . m
# Stuck cells (dry friction) shaded by their end |q|: light grey small, dark large, up to
# stuck_max [m] (the largest stuck cell's, given by the command; named in the title), so that a
# dry basin is not one uniform square.
if (!exists("stuck_max")) stuck_max = 0
stuck_max = stuck_max + 0.0
level(q) = int(215 - 150 * (stuck_max > 0 ? q / stuck_max : 0))
grey(q) = level(q) * 65536 + level(q) * 256 + level(q)
if (stuck_max > 0) { set title title . sprintf("\nstuck cells shaded by their end |q|: light small, dark up to %.3g µm", stuck_max * 1e6) noenhanced }
cells_layer = "csv using (column('beta1_0') + h1):(column('beta2_0') + h2):(idx(class(strcol('attractor'), strcol('member')), 1)) with image pixels notitle"
stuck_layer = "csv using (strcol('attractor') eq 'stuck' ? column('beta1_0') + h1 : 1/0):(column('beta2_0') + h2):(h1):(h2):(grey(column('q_abs_end'))) with boxxyerror fs solid noborder lc rgb variable notitle"
if (stuck_max > 0) { eval('plot ' . cells_layer . ', ' . stuck_layer) } else { eval('plot ' . cells_layer) }
