# The shared look of the trade-off plots (tools/run-tradeoff.sh). A script
# loads it, then sets its output:
#   gnuplot -e "load '$TRADEOFF_DIR/style.gp'; set output '$OUT/x.png'; ..."
# Small PNGs: they are committed in docs/tradeoff/.
set terminal pngcairo size 760,500 font "DejaVu Sans,10" noenhanced
set datafile separator ","
set key top left box opaque
set grid xtics ytics mxtics mytics lc rgb "#dddddd" lw 1
set border lw 1
set tics nomirror out
set style data linespoints
set pointsize 1
# line styles 1..8: distinguishable colours, one point type each
set style line 1 lc rgb "#1f77b4" lw 2 pt 7
set style line 2 lc rgb "#d62728" lw 2 pt 5
set style line 3 lc rgb "#2ca02c" lw 2 pt 9
set style line 4 lc rgb "#9467bd" lw 2 pt 11
set style line 5 lc rgb "#ff7f0e" lw 2 pt 13
set style line 6 lc rgb "#8c564b" lw 2 pt 3
set style line 7 lc rgb "#e377c2" lw 2 pt 1
set style line 8 lc rgb "#7f7f7f" lw 2 pt 2
set style increment user
# log-scale helpers: call them with `eval logx` etc.
logx = "set logscale x; set format x '10^{%L}'; set mxtics 10"
logy = "set logscale y; set format y '10^{%L}'; set mytics 10"
logxy = "set logscale xy; set format x '10^{%L}'; set format y '10^{%L}'; set mxtics 10; set mytics 10"
# the format strings need the enhanced mode for the exponents
set termoption enhanced
