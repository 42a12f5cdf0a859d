# Shape of Dal Corso et al. Fig. 9: error at equal time against the converged BSSRDF reference, at three scales
# (bunny 10 mm, 100 mm, 1 m wide): radiosity-maps after one frame versus the BSSRDF reference ray tracer given
# the same wall time. Called by `lucent bench bench/fig9_scales.json` with tsv and out set.
set terminal pngcairo size 820,460 font ",11"
set output out
set datafile separator "\t"
set datafile columnheaders
set key top right
set logscale x
set xlabel "bunny width [mm]"
set ylabel "RMSE sqrt(dr^2+dg^2+db^2) vs converged reference"
set grid
plot tsv using (column("scale_mm") * 2):"rmse_bssrdf" with linespoints lw 2 pt 7 title "radiosity-maps, 1 frame", \
     tsv using (column("scale_mm") * 2):"rmse_equal_time_bssrdf" with linespoints lw 2 pt 5 title "BSSRDF ray tracer, equal time"
