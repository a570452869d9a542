# The distribution of a study's outcomes (`stability-scan outcomes`, docs/model.md §21): left, the
# empirical distribution functions of the residual |q| at the end and of the peak |q| on the way
# [µm], with the bare rotor's |q| (16.5.1, the runs' median) marked; right, the residual against
# the bare rotor's per run (1: the balls do nothing) over ball 1's start angle, stuck runs grey,
# stalled red, balanced green.
# Re-run by hand with
#   gnuplot -e "csv='out/outcomes/outcomes.csv'; png='o.png'; columns=2; runs=256; bare=4.1; title='x'" plots/outcomes.gp
# columns: balls + uncertain inputs (the columns between `sample` and `outcome`); runs: data rows;
# bare: the bare rotor's median |q| [µm].
if (!exists("csv")) csv = 'out/outcomes/outcomes.csv'
if (!exists("png")) png = 'outcomes.png'
if (!exists("columns")) columns = 2
if (!exists("runs")) runs = 1
if (!exists("bare")) bare = 0
if (!exists("title")) title = ''
columns = columns + 0
runs = runs + 0
bare = bare + 0.0
set datafile separator ','
set datafile commentschars '#'
set datafile missing ''
c_outcome = columns + 2
c_residual = columns + 3
c_ratio = columns + 6
c_peak = columns + 8
c_stalled = columns + 10
set terminal pngcairo size 1200, 520 font ',10'
set output png
set multiplot layout 1, 2 title title noenhanced
set key center right
set grid
set xlabel '|q| [µm]'
set xrange [0:*]
set ylabel 'fraction of runs'
set yrange [0:1.02]
set arrow 1 from bare, graph 0 to bare, graph 1 nohead dashtype 2 lc rgb '#444444'
set label 1 sprintf('bare rotor %.3g µm', bare) at bare, graph 0.96 offset 0.5, 0 font ',9'
plot csv every ::1 using (column(c_residual) * 1e6):(1.0 / runs) smooth cumulative lw 2 lc rgb '#1f77b4' \
       title 'residual at the end', \
     csv every ::1 using (column(c_peak) * 1e6):(1.0 / runs) smooth cumulative lw 2 lc rgb '#d62728' \
       title 'peak on the way'
unset arrow 1
unset label 1
set xlabel 'start angle of ball 1 [rad]'
set ylabel 'residual / bare rotor'
set autoscale y
set logscale y
set xrange [0:2 * pi]
set key top right
kind(s, st) = st > 0 ? 2 : (s eq 'balanced' ? 0 : (s eq 'stuck' ? 1 : 3))
plot 1 with lines dashtype 2 lc rgb '#444444' title 'bare rotor', \
     csv every ::1 using 2:(kind(strcol(c_outcome), column(c_stalled)) == 0 ? column(c_ratio) : 1/0) \
       with points pt 7 ps 0.5 lc rgb '#2ca02c' title 'balanced', \
     csv every ::1 using 2:(kind(strcol(c_outcome), column(c_stalled)) == 1 ? column(c_ratio) : 1/0) \
       with points pt 7 ps 0.5 lc rgb '#7f7f7f' title 'stuck away from balance', \
     csv every ::1 using 2:(kind(strcol(c_outcome), column(c_stalled)) == 2 ? column(c_ratio) : 1/0) \
       with points pt 7 ps 0.5 lc rgb '#d62728' title 'stalled', \
     csv every ::1 using 2:(kind(strcol(c_outcome), column(c_stalled)) == 3 ? column(c_ratio) : 1/0) \
       with points pt 7 ps 0.5 lc rgb '#1f77b4' title 'other (periodic, aligned, not settled)'
unset multiplot
