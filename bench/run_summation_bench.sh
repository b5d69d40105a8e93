#!/usr/bin/env bash
# What the fixed summation order and the rest of the core cost against a build of another revision
# (bench/results/summation.md): instructions per particle-step inside Simulation::advance, one
# thread, under valgrind's callgrind, for the chute (200 steps) and the settles of 10^4 (2,000
# steps) and 10^5 (300 steps), this tree's build against BASE_BUILD's (e.g. 11712ad, the last
# commit before the summation order), by groups of functions (bench/callgrind_groups.py).
# Instruction counts, not times: exact, where timings on a shared VM spread by up to 2x.
# Usage: bash bench/run_summation_bench.sh BASE_BUILD   (from anywhere; about 6 minutes on one core)
set -euo pipefail
cd "$(dirname "$0")/.."
base_build=$(cd "$1" && pwd)
cmake --build build --target settle_bench chute_bench -- --no-print-directory > /dev/null
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
args=()
for spec in "chute:chute_bench run 200:200:32000" "settle10k:settle_bench run 10000 2000:2000:10000" "settle100k:settle_bench run 100000 300:300:100000"; do
  IFS=: read -r name command steps particles <<< "$spec"
  for side in base this; do
    dir=$PWD/build; [ $side = base ] && dir=$base_build
    set -- $command
    OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$tmp/$name.$side" --toggle-collect='dem::Simulation::advance()' \
      "$dir/bench/$1" "${@:2}" 1 > /dev/null 2>&1
  done
  args+=("$tmp/$name.base:$tmp/$name.this:$steps:$particles")
done
python3 bench/callgrind_groups.py "${args[@]}"
