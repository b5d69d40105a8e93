#!/usr/bin/env bash
# Our code beside LIGGGHTS 3.8 on the physics (issue 31, verification 3), Hertz-Mindlin with EPSD2
# rolling resistance in both (`pair gran model hertz tangential history rolling_friction epsd2`):
# 1. settle: the spheres of tests/reference/liggghts_settle/settle.env falling into their box from
#    the same states in both codes (a seed draws the initial velocities): kinetic energy and mean
#    coordination over time; LIGGGHTS's runs become the suite test's reference
#    (tests/reference/liggghts_settle/liggghts.csv), ours go beside them;
# 2. heap: 3,000 spheres poured onto a floor (bench/peers/heap.toml, in.heap.liggghts), four
#    insertion seeds a code; the repose angle of each final heap measured by one script
#    (side_by_side.py heap-angle).
# Writes bench/results/peers_physics_settle_runs.csv, peers_physics_heap.csv and the plots
# peers_physics_*.png; prints the comparisons (bench/results/peers_physics.md quotes them).
# Usage: bash bench/peers/run_side_by_side.sh [PARTS]   (PARTS: "settle heap", the default; about
#   1 min for the settle and 5 min for the heap on one core of the 2-core machine)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
parts=${1:-"settle heap"}
py=/usr/bin/python3
sbs=$root/bench/peers/side_by_side.py
ref=$root/tests/reference/liggghts_settle
res=$root/bench/results
cmake --build build --target settle_bench gen-primary run-stage -- --no-print-directory > /dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [[ " $parts " == *" settle "* ]]; then
  bash "$ref/run_liggghts.sh" build/bench/settle_bench "$ref/liggghts.csv"
  source "$ref/settle.env"
  echo "seed,step,time_s,ke_J,rke_J,coordination" > "$tmp/ours.csv"
  for seed in $SEEDS; do
    OMP_NUM_THREADS=1 build/bench/settle_bench series "$N" "$STEPS" "$EVERY" "$seed" hertz-rolling | tail -n +2 | sed "s/^/$seed,/" >> "$tmp/ours.csv"
  done
  { echo "code,seed,step,time_s,ke_J,rke_J,coordination"
    tail -n +2 "$tmp/ours.csv" | sed 's/^/dem,/'
    tail -n +2 "$ref/liggghts.csv" | sed 's/^/liggghts,/'; } > "$res/peers_physics_settle_runs.csv"
  "$py" "$sbs" settle "$tmp/ours.csv" "$ref/liggghts.csv" "$N" --table || true
fi

if [[ " $parts " == *" heap "* ]]; then
  echo "code,seed,angle_deg,particles" > "$res/peers_physics_heap.csv"
  build/tools/gen-primary --scene bench/peers/heap.toml --out "$tmp/start.h5" --quiet
  for seed in 1 2 3 4; do
    sed "s/^seed = 1$/seed = $seed/" bench/peers/heap.toml > "$tmp/heap.toml"
    OMP_NUM_THREADS=1 build/tools/run-stage --scene "$tmp/heap.toml" --stage pour --in "$tmp/start.h5" --out "$tmp/heap.h5" --quiet
    "$py" "$sbs" checkpoint-positions "$tmp/heap.h5" > "$tmp/dem.$seed.csv"
    echo "dem,$seed,$("$py" "$sbs" heap-angle "$tmp/dem.$seed.csv"),$(($(wc -l < "$tmp/dem.$seed.csv") - 1))" | tee -a "$res/peers_physics_heap.csv"
  done
  for seed in 10007 10009 10037 10039; do  # LIGGGHTS asks for primes above 10,000
    (cd "$tmp" && liggghts -in "$root/bench/peers/in.heap.liggghts" -var seed "$seed" -var out "$tmp/heap.dump" -log none > /dev/null)
    "$py" "$sbs" dump-final "$tmp/heap.dump" > "$tmp/liggghts.$seed.csv"
    echo "liggghts,$seed,$("$py" "$sbs" heap-angle "$tmp/liggghts.$seed.csv"),$(($(wc -l < "$tmp/liggghts.$seed.csv") - 1))" | tee -a "$res/peers_physics_heap.csv"
  done
  "$py" "$sbs" heap "$res/peers_physics_heap.csv" || true
  "$py" "$sbs" heap-plot "$res/peers_physics_heap.png" "$tmp"/dem.*.csv -- "$tmp"/liggghts.*.csv || true
fi
[[ " $parts " == *" settle "* ]] && "$py" "$sbs" settle-plot "$res/peers_physics_settle_runs.csv" "$res/peers_physics_settle.png" || true
