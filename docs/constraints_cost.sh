#!/bin/sh
# The cloth's largest stick error against its cost (docs/constraints.md): scenes/cloth.json run by
# `motus run` with the projection set three ways, and Bullet's cloth from `motus compare`, into
# docs/constraints_cost.csv and the plot docs/pictures/constraints_cost.png (gnuplot). Every row's
# time is the fastest of the same ROUNDS runs (`--repeats`); its error is over every step.
#   docs/constraints_cost.sh              uses build/motus
#   MOTUS=build-x/motus docs/constraints_cost.sh
#   PLOT_ONLY=1 docs/constraints_cost.sh  redraws the plot from the CSV as it is
set -eu
cd "$(dirname "$0")/.."
MOTUS=${MOTUS:-build/motus}
CSV=docs/constraints_cost.csv
ROUNDS=5
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# One run: LABEL SUBSTEPS SWEEPS -> a CSV line: label,substeps,sweeps,us_min,us_median,largest stick error
run() {
  "$MOTUS" run cloth --json --repeats "$ROUNDS" --set constraint_substeps="$2" --set constraint_iterations="$3" >"$WORK/run.json"
  python3 -c "
import json
j = json.load(open('$WORK/run.json'))
t = j['ns_per_step']
print('$1,$2,$3,%.2f,%.2f,%.4e' % (t['min'] / 1e3, t['median'] / 1e3, j['constraint_error']['max']))"
}

if [ -z "${PLOT_ONLY:-}" ]; then
{
  echo "series,substeps,sweeps,us_per_step_min,us_per_step_median,largest_stick_error"
  for s in 12 25 50 100 200; do run "one step of N sweeps in scene order" 1 "$s"; done
  for n in 4 8 16 32 64 128; do run "substeps of one sweep (colours)" "$n" 1; done
  for n in 4 8 16 32; do run "substeps of four sweeps (colours)" "$n" 4; done
  "$MOTUS" compare cloth --json --engines bullet --repeats "$ROUNDS" --out "$WORK/compare" >"$WORK/compare.json"
  python3 -c "
import json
e = json.load(open('$WORK/compare.json'))['engines'][0]
print('Bullet 3 (its own constraint solver),1,10,%.2f,%.2f,%.4e' % (e['us_per_step'], e['us_per_step_median'], e['constraint_error']))"
} >"$WORK/csv"
mv "$WORK/csv" "$CSV"  # only a complete table replaces the old one
fi
cat "$CSV"

gnuplot <<GNUPLOT
set terminal pngcairo size 720,440 font ",10"
set output "docs/pictures/constraints_cost.png"
set datafile separator ","
set logscale xy
set xlabel "CPU time per step of 1/240 s [µs] (the fastest of $ROUNDS runs)"
set ylabel "largest stick error over every step of the 6 s (relative)"
set title "cloth.json (20 x 20, 1,482 sticks): error against cost"
set key bottom left
set grid
set format y "10^{%L}"
plot "< grep 'scene order' $CSV" using 4:6 with linespoints pt 7 title "one step, N sweeps in the scene order", \
     "< grep 'of one sweep' $CSV" using 4:6 with linespoints pt 5 title "n substeps of one sweep, in colours", \
     "< grep 'of four sweeps' $CSV" using 4:6 with linespoints pt 9 title "n substeps of four sweeps", \
     "< grep Bullet $CSV" using 4:6 with points pt 13 ps 2 title "Bullet 3.24, same scene", \
     0.01 with lines dt 2 lc rgb "gray" title "1 %"
GNUPLOT
echo "docs/pictures/constraints_cost.png  $(wc -c <docs/pictures/constraints_cost.png) bytes"
