#!/usr/bin/env bash
# The peer bench's linear rows, our benches only, this tree's build against BASE_BUILD's (e.g.
# 11712ad, the last commit before the fixed summation order; bench/results/summation.md), at the
# peer bench's sizes, one and two threads (one pinned to CPU 0), each row's two builds run back to
# back, ROUNDS rounds. Prints CSV: round, threads, row, base loop_s, this loop_s, time (UTC).
# The base build's benches take no model argument (they predate Hertz); this tree's take `linear`.
# Usage: bash bench/run_summation_rows.sh BASE_BUILD [ROUNDS=5]   (about 6 minutes on the 2-core VM)
set -euo pipefail
cd "$(dirname "$0")/.."
base=$(cd "$1" && pwd)/bench
rounds=${2:-5}
cmake --build build --target settle_bench chute_bench -- --no-print-directory > /dev/null
loop_s() { grep -o "loop_s [0-9.]*" | cut -d' ' -f2; }
echo "round,threads,row,base_loop_s,this_loop_s,utc"
for round in $(seq 1 "$rounds"); do
  for t in 1 2; do
    on=(); [ "$t" = 1 ] && on=(taskset -c 0)
    for row in "chute_bench run 6000" "settle_bench run 10000 20000" "settle_bench run 100000 2500"; do
      read -r -a cmd <<< "$row"
      a=$(OMP_NUM_THREADS=$t "${on[@]}" "$base/${cmd[0]}" "${cmd[@]:1}" "$t" | loop_s)
      b=$(OMP_NUM_THREADS=$t "${on[@]}" "build/bench/${cmd[0]}" "${cmd[@]:1}" "$t" linear | loop_s)
      echo "$round,$t,${cmd[0]} ${cmd[2]},$a,$b,$(date -u +%H:%M:%S)"
    done
  done
done
