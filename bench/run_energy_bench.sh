#!/usr/bin/env bash
# What the energy log costs (sim/energy_ledger.hpp, run/energy_log.hpp): the quickstart bed (300
# glass beads settled in a box, workflows/quickstart/scene.toml) shaken for the first cycle of its
# stage "shake" (0.05 s at 20 Hz and 3 g) by run-stage on one thread under valgrind's
# callgrind: instructions per step inside Simulation::advance (inclusive), with the energy log off
# for a build of another revision (BASE_BUILD: its tools/run-stage; e.g. main's HEAD before the
# change) and for this tree's build, and with the log on for both (--energy-every 1000: the
# ledger's pass runs every step, a row every 1,000). Instruction counts, not times: the machine is
# shared and timings are noise at this level. Writes the head of bench/results/energy.md, up to its
# first "## " section, which is kept (the impact stage's measurements).
# Usage: bash bench/run_energy_bench.sh BASE_BUILD BASE_NAME   (from the repository root; about
# 3 minutes on one core)
set -euo pipefail
cd "$(dirname "$0")/.."
base_build=$1 base_name=$2
for b in build "$base_build"; do
  [ -x "$b/tools/run-stage" ] || { echo "no $b/tools/run-stage: build it first (cmake --build $b -j2)"; exit 1; }
done
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# The quickstart scene with its stage cut to one cycle.
sed 's/^duration = 0.25 .*/duration = 0.05/' workflows/quickstart/scene.toml > "$tmp/scene.toml"
grep -q '^duration = 0.05$' "$tmp/scene.toml" || { echo "the quickstart scene's shake duration was not found"; exit 1; }
OMP_NUM_THREADS=1 build/tools/gen-primary --scene "$tmp/scene.toml" --out "$tmp/settled.h5" --quiet
measure() {  # label, build, extra run-stage options -> "advance_Ir steps"
  local out=$tmp/$1
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out.cg" "$2/tools/run-stage" --scene "$tmp/scene.toml" \
    --stage shake --in "$tmp/settled.h5" --out "$out.h5" --checkpoint-minutes 0 --health-every 100000000 "${@:3}" 2> "$out.log"
  callgrind_annotate --inclusive=yes --threshold=100 "$out.cg" > "$out.txt"
  local advance steps
  advance=$(grep "dem::Simulation::advance()" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}')
  # The stage's steps, from run-stage's summary line ("stage shake done: N steps in ...").
  steps=$(sed -n 's/.*stage shake done: \([0-9]*\) steps.*/\1/p' "$out.log")
  [ -n "$steps" ] || { echo "no summary line in $out.log" >&2; exit 1; }
  echo "$advance $steps"
}
read -r a_base s_base <<< "$(measure base "$base_build")"
read -r a_off s_off <<< "$(measure off build)"
read -r a_on s_on <<< "$(measure on build --energy-every 1000)"
read -r a_base_on s_base_on <<< "$(measure base_on "$base_build" --energy-every 1000)"
per() { awk -v a="$1" -v s="$2" 'BEGIN { printf "%.0f", a / s }'; }
rel() { awk -v a="$1" -v s="$2" -v b="$3" -v t="$4" 'BEGIN { printf "%+.3f", 100 * ((a / s) / (b / t) - 1) }'; }
out=bench/results/energy.md
kept=$(sed -n '/^## /,$p' "$out" 2> /dev/null || true)
{
  echo "# What the energy log costs"
  echo
  echo "Measured $(date -u +%Y-%m-%d) with \`bash bench/run_energy_bench.sh BASE_BUILD $base_name\` (valgrind"
  echo "$(valgrind --version | sed 's/valgrind-//'), callgrind instruction counts, one thread; Release builds; BASE_BUILD a build of"
  echo "revision $base_name)."
  echo
  echo "The quickstart bed (\`workflows/quickstart/scene.toml\`: 300 glass beads settled in a box) shaken"
  echo "for the first cycle of its stage \`shake\` (0.05 s at 20 Hz and 3 g, $s_off steps; the health log once, at the"
  echo "end) by \`run-stage\`."
  echo "The figure is the instructions inside \`Simulation::advance\` (inclusive: contacts, forces, motion"
  echo "and, when on, the ledger's pass) per step."
  echo
  echo "| build | energy log | instructions per step | against $base_name, log off |"
  echo "|---|---|---|---|"
  echo "| $base_name | off | $(per "$a_base" "$s_base") | – |"
  echo "| this tree | off | $(per "$a_off" "$s_off") | $(rel "$a_off" "$s_off" "$a_base" "$s_base") % |"
  echo "| $base_name | on (\`--energy-every 1000\`) | $(per "$a_base_on" "$s_base_on") | $(rel "$a_base_on" "$s_base_on" "$a_base" "$s_base") % |"
  echo "| this tree | on (\`--energy-every 1000\`) | $(per "$a_on" "$s_on") | $(rel "$a_on" "$s_on" "$a_base" "$s_base") % |"
  echo
  echo "Off, both builds do the same work per step (the ledger costs one test of \`ledger.on\`); a"
  echo "difference of a few tenths of a percent is the compiler's placement of the code. On, the"
  echo "ledger's pass walks the particles and the contacts once more per step (docs/physics.md P29-P45),"
  echo "split over the threads (one here: the count is the work, not the wall time); it is meant for"
  echo "diagnosis and for the cases' balances, not for production runs that do not ask for it. What is"
  echo "held is measured only at the log's rows; the work is added every step."
  [ -z "$kept" ] || printf '\n%s\n' "$kept"
} > "$out.new"
mv "$out.new" "$out"
cat "$out"
