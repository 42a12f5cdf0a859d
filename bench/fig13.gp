# Shape of Dal Corso et al. Fig. 13: GPU time per frame and coverage of the visible surface against K.
# Called by `lucent bench bench/fig13_k_sweep.json` with tsv and out set.
set terminal pngcairo size 820,460 font ",11"
set output out
set datafile separator "\t"
set datafile columnheaders  # results.tsv names its columns; read them by name
set key top left
set xlabel "K (scattered-radiosity maps)"
set ylabel "time per frame [ms]"
set y2label "visible surface covered"
set y2range [0:1.05]
set ytics nomirror
set y2tics
set grid
plot tsv using "K":"total_ms" with linespoints lw 2 pt 7 title "total (median)", \
     tsv using "K":(column("ms:map_gbuffers") + column("ms:integrate")) with linespoints lw 2 pt 5 \
         title "step 2: radiosity maps", \
     tsv using "K":"coverage" axes x1y2 with linespoints lw 2 pt 9 title "coverage"
