# Shape of Dal Corso et al. Fig. 11: frame time against the share of the image the translucent object covers,
# for radiosity-maps (cached) and per-pixel (no cache); lines fitted to each, the break-even where they cross.
# Called by `lucent bench bench/fig11_break_even.json` with tsv and out set (columns read by name: total_ms,
# method, occupancy).
set terminal pngcairo size 820,460 font ",11"
set output out
set datafile separator "\t"
set datafile columnheaders
set key top left
set xlabel "occupancy (share of the image covered by the translucent object)"
set ylabel "time per frame [ms]"
set grid
maps(x) = a1 * x + b1
pixel(x) = a2 * x + b2
a1 = 1; b1 = 1; a2 = 1; b2 = 1
set fit quiet logfile '/dev/null'
fit maps(x) tsv using "occupancy":(strcol("method") eq "radiosity-maps" ? column("total_ms") : 1/0) via a1, b1
fit pixel(x) tsv using "occupancy":(strcol("method") eq "per-pixel" ? column("total_ms") : 1/0) via a2, b2
break_even = (b1 - b2) / (a2 - a1)
set title sprintf("break-even occupancy %.1f%% (fitted lines cross)", 100 * break_even)
set arrow from break_even, graph 0 to break_even, graph 1 nohead dt 2
plot tsv using "occupancy":(strcol("method") eq "radiosity-maps" ? column("total_ms") : 1/0) with points pt 7 ps 1.3 title "radiosity-maps (10 maps)", \
     tsv using "occupancy":(strcol("method") eq "per-pixel" ? column("total_ms") : 1/0) with points pt 5 ps 1.3 title "per-pixel (no cache)", \
     maps(x) with lines lw 2 notitle, pixel(x) with lines lw 2 notitle
