# Shape of Dal Corso et al. Fig. 13: GPU time per frame and coverage of the visible surface against K.
# Called by `lucent bench bench/fig13_k_sweep.json` with tsv and out set.
set terminal pngcairo size 820,460 font ",11"
set output out
set datafile separator "\t"
set key top left
set xlabel "K (scattered-radiosity maps)"
set ylabel "time per frame [ms]"
set y2label "visible surface covered"
set y2range [0:1.05]
set ytics nomirror
set y2tics
set grid
plot tsv using 3:6 skip 1 with linespoints lw 2 pt 7 title "total (median)", \
     tsv using 3:7 skip 1 with linespoints lw 2 pt 5 title "step 2: radiosity maps", \
     tsv using 3:8 skip 1 axes x1y2 with linespoints lw 2 pt 9 title "coverage"
