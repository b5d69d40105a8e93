#!/usr/bin/env bash
# Writes liggghts.csv, the reference of the suite test reference.liggghts_settle (check_ours.sh):
# the settle of settle.env in LIGGGHTS 3.8 (bench/peers/in.settle_hertz.liggghts, `pair gran model
# hertz tangential history rolling_friction epsd2`), one run per seed from the state that
# `settle_bench lammps-data N FILE SEED` writes (the same as our runs start from): translational
# and rotational kinetic energy and mean coordination (compute contact/atom summed / N) every EVERY
# steps. Needs LIGGGHTS (Debian: apt-get install liggghts; made with 3.8.0+repack1-9+b2).
# Usage: run_liggghts.sh SETTLE_BENCH [OUT.csv]   (about 10 s a seed on one core)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bench=$(realpath "$1")
out=$(realpath -m "${2:-$here/liggghts.csv}")
source "$here/settle.env"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "seed,step,time_s,ke_J,rke_J,coordination" > "$out.tmp"
for seed in $SEEDS; do
  "$bench" lammps-data "$N" "$tmp/data" "$seed"
  (cd "$tmp" && liggghts -in "$here/../../../bench/peers/in.settle_hertz.liggghts" -var N "$N" -var nsteps "$STEPS" -var rolling 1 \
     -var every "$EVERY" -var datafile "$tmp/data" -log "$tmp/log" > /dev/null)
  /usr/bin/python3 "$here/../../../bench/peers/side_by_side.py" lammps-log "$tmp/log" | tail -n +2 |
    awk -F, -v s="$seed" '{printf "%s,%s,%.9g,%s,%s,%s\n", s, $1, $1 * 5e-6, $2, $3, $4}' >> "$out.tmp"
done
mv "$out.tmp" "$out"
echo "wrote $out"
