#!/usr/bin/env bash
# This tree's build against another build (BASE_BUILD: e.g. a worktree of main's HEAD before the
# change, `git worktree add /tmp/base HEAD && cmake -S /tmp/base -B /tmp/base/build
# -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/base/build -j2 --target settle_bench run-stage`),
# on the scenes the speed issues are measured on, the two builds' runs interleaved so that both
# see the same hour of a shared machine (its pace drifts by 5-10 % within an hour: compare only
# runs made side by side):
# - the Hertz settle of 10^4 spheres with the explicit dashpot (`settle_bench run 10000 20000 1
#   hertz-explicit`), one thread pinned to CPU $PIN_CPU (default 0);
# - with HELICAL_BED (a settled helical-flow bed: `build/tools/gen-primary --scene
#   workflows/helical-flow/scene.toml --out BED --threads 2`, about 5 minutes), the helical-flow
#   `bench` stage (5,000 steps of the spin) with the energy log, on two threads.
# Each run's loop time, the medians, and whether the two builds' results are the same bits (the
# settle's energies; the helical stage's energy and health logs).
# Usage: bash bench/run_ab_bench.sh BASE_BUILD [ROUNDS (default 3)] [HELICAL_BED]
#   (from the repository root; about 25 s a settle pair and 15 s a helical pair)
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: bash bench/run_ab_bench.sh BASE_BUILD [ROUNDS] [HELICAL_BED]" >&2; exit 2; }
base=$1 rounds=${2:-3} bed=${3:-}
pin=${PIN_CPU:-0}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "ROUNDS must be a positive whole number, not '$rounds'" >&2; exit 2; }
for b in build "$base"; do
  [ -x "$b/bench/settle_bench" ] || { echo "no $b/bench/settle_bench: build it first (cmake --build $b -j2 --target settle_bench run-stage)" >&2; exit 1; }
  if [ -n "$bed" ]; then
    [ -x "$b/tools/run-stage" ] || { echo "no $b/tools/run-stage: build it first" >&2; exit 1; }
  fi
done
[ -z "$bed" ] || [ -f "$bed" ] || { echo "HELICAL_BED '$bed' is not a file" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

median() { sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

settle() {  # build, label -> appends its loop time to $tmp/settle.<label>, its energies to .bits
  local out
  out=$(OMP_NUM_THREADS=1 taskset -c "$pin" "$1/bench/settle_bench" run 10000 20000 1 hertz-explicit 2>/dev/null | tail -1)
  grep -qE 'loop_s [0-9.]+' <<<"$out" || { echo "settle_bench of $1 failed: $out" >&2; exit 1; }
  grep -oE 'loop_s [0-9.]+' <<<"$out" | awk '{print $2}' >> "$tmp/settle.$2"
  grep -oE '\bke [0-9.e+-]+|rke [0-9.e+-]+' <<<"$out" | tr '\n' ' ' > "$tmp/settle.$2.bits"
}
helical() {  # build, label
  local out
  out=$(OMP_NUM_THREADS=2 "$1/tools/run-stage" --scene workflows/helical-flow/scene.toml --stage bench --in "$bed" \
    --out "$tmp/helical.$2.h5" --energy-every 0.01s --checkpoint-minutes 0 2>&1)
  grep -qE 'done: [0-9]+ steps in [0-9.]+ s' <<<"$out" || { echo "run-stage of $1 failed: $(tail -3 <<<"$out")" >&2; exit 1; }
  grep -oE 'done: [0-9]+ steps in [0-9.]+ s' <<<"$out" | awk '{print $5}' >> "$tmp/helical.$2"
}

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
echo "# this tree: $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- lib || echo ' with uncommitted changes to lib/'); base: $base"
for r in $(seq "$rounds"); do
  settle "$base" base; settle build this
  if [ -n "$bed" ]; then helical "$base" base; helical build this; fi
  echo "# round $r of $rounds done" >&2
done

echo
echo "| scene | build | loop s (each run, in order) | median |"
echo "|---|---|---|---|"
scenes=settle
[ -z "$bed" ] || scenes="settle helical"
for s in $scenes; do
  for l in base this; do
    echo "| $s | $l | $(paste -sd' ' "$tmp/$s.$l" | sed 's/ / \/ /g') | $(median < "$tmp/$s.$l") |"
  done
done
echo
same() { cmp -s "$1" "$2" && echo "the same bits" || echo "DIFFERENT"; }
echo "- settle's energies: $(same "$tmp/settle.base.bits" "$tmp/settle.this.bits")"
if [ -n "$bed" ]; then
  echo "- helical stage's energy log: $(same "$tmp/helical.base.energy.csv" "$tmp/helical.this.energy.csv")"
  echo "- helical stage's health log: $(same "$tmp/helical.base.health.csv" "$tmp/helical.this.health.csv")"
fi
