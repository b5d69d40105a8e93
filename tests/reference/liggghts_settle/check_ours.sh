#!/usr/bin/env bash
# The suite test reference.liggghts_settle: our side of the settle comparison of settle.env
# (settle_bench series, one thread, every seed) against the stored LIGGGHTS runs (liggghts.csv,
# made by run_liggghts.sh): at every output the seed means of the kinetic energy and of the mean
# coordination must differ by at most k x the pooled seed deviation (bench/peers/side_by_side.py
# gives k: Student's t with a Bonferroni correction over the outputs, alpha = 0.05).
# Usage: check_ours.sh SETTLE_BENCH [FRICTION ROLLING_FRICTION]  (a changed material must fail)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bench=$1; shift
source "$here/settle.env"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "seed,step,time_s,ke_J,rke_J,coordination" > "$tmp/ours.csv"
for seed in $SEEDS; do
  OMP_NUM_THREADS=1 "$bench" series "$N" "$STEPS" "$EVERY" "$seed" hertz-rolling "$@" > "$tmp/run.csv" || { echo "FAIL: settle_bench series"; exit 1; }
  tail -n +2 "$tmp/run.csv" | sed "s/^/$seed,/" >> "$tmp/ours.csv"
done
/usr/bin/python3 "$here/../../../bench/peers/side_by_side.py" settle "$tmp/ours.csv" "$here/liggghts.csv" "$N"
