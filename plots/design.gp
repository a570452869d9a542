# A design study's chart (`stability-scan design`, docs/model.md §22): left, the objective
# against the total ball mass, every feasible design grey, the Pareto front joined, the
# recommended design a star and the scene's own design a square; right, the objective against
# the first design variable, feasible designs filled, infeasible ones open, and for a residual
# objective the bare rotor's |q| of each design (crosses).
# Re-run by hand with
#   gnuplot -e "csv='out/design/design.csv'; png='d.png'; variables=2; constraints=1; xname='m'; objective='x'" plots/design.gp
# Columns (design.csv): design, origin, the variables, feasible, objective, g1.., ball_mass, ...
if (!exists("csv")) csv = 'out/design/design.csv'
if (!exists("png")) png = 'design.png'
if (!exists("variables")) variables = 1
if (!exists("constraints")) constraints = 0
if (!exists("xname")) xname = 'x'
if (!exists("xlog")) xlog = 0
if (!exists("objective")) objective = 'objective'
if (!exists("percent")) percent = 0
if (!exists("micron")) micron = 0
if (!exists("title")) title = ''
variables = variables + 0
constraints = constraints + 0
percent = percent + 0
micron = micron + 0
xlog = xlog + 0
c_x = 3
c_feasible = 3 + variables
c_objective = c_feasible + 1
c_mass = c_objective + constraints + 1
c_bare = c_mass + 11
c_pareto = c_mass + 12
c_recommended = c_pareto + 1
scale = percent ? 100 : (micron ? 1e6 : 1)
unit = percent ? ' [%]' : (micron ? ' [µm]' : '')
set datafile separator ','
set datafile commentschars '#'
set datafile missing ''
set terminal pngcairo size 1200, 520 font ',10'
set output png
set multiplot layout 1, 2 title title noenhanced
set grid
set key bottom right
set xlabel 'total ball mass [kg]'
set format x '%.3g'
stats csv every ::1 using c_mass nooutput
if (STATS_min == STATS_max) { set xrange [0.9 * STATS_min : 1.1 * STATS_max] }
set ylabel objective . unit noenhanced
plot csv every ::1 using (column(c_feasible) == 1 ? column(c_mass) : 1/0):(column(c_objective) * scale) \
       with points pt 7 ps 0.6 lc rgb '#aaaaaa' title 'feasible designs', \
     csv every ::1 using (column(c_pareto) == 1 ? column(c_mass) : 1/0):(column(c_objective) * scale) \
       with linespoints pt 7 ps 0.9 lw 2 lc rgb '#1f77b4' title 'Pareto front', \
     csv every ::1 using (strcol(2) eq 'scene' ? column(c_mass) : 1/0):(column(c_objective) * scale) \
       with points pt 5 ps 1.6 lc rgb '#d62728' title "the scene's design", \
     csv every ::1 using (column(c_recommended) == 1 ? column(c_mass) : 1/0):(column(c_objective) * scale) \
       with points pt 3 ps 2.5 lw 2 lc rgb '#2ca02c' title 'recommended'
set xlabel xname noenhanced
set autoscale x
set format x '%g'
if (xlog) { set logscale x }
if (xname eq 'n') { set xtics 1; set offsets 0.5, 0.5, 0, 0 }
plot csv every ::1 using (micron ? column(c_x) : 1/0):(column(c_bare) * scale) \
       with points pt 2 ps 0.8 lc rgb '#444444' title 'bare rotor (16.5.1)', \
     csv every ::1 using (column(c_feasible) == 1 ? column(c_x) : 1/0):(column(c_objective) * scale) \
       with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'feasible', \
     csv every ::1 using (column(c_feasible) == 0 ? column(c_x) : 1/0):(column(c_objective) * scale) \
       with points pt 6 ps 0.8 lc rgb '#d62728' title 'infeasible', \
     csv every ::1 using (strcol(2) eq 'scene' ? column(c_x) : 1/0):(column(c_objective) * scale) \
       with points pt 5 ps 1.6 lc rgb '#d62728' title "the scene's design", \
     csv every ::1 using (column(c_recommended) == 1 ? column(c_x) : 1/0):(column(c_objective) * scale) \
       with points pt 3 ps 2.5 lw 2 lc rgb '#2ca02c' title 'recommended'
unset multiplot
