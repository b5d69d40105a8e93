#!/bin/sh
# The fluid drag's cost (bench/results/drag.md): callgrind instruction counts of run-stage's steps
# (Simulation::advance only) on bench/drag/scene.toml, with the fluid (stage `well`) and without
# (stage `dry`), one thread. Usage: bench/run_drag_bench.sh BUILD_DIR OUT_DIR
set -e
build=${1:-build}; out=${2:-/tmp/drag_bench}
src=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
[ -e "$out/pack.h5" ] || "$build/tools/gen-primary" --scene "$src/drag/generate.toml" --out "$out/pack.h5" --quiet
for stage in well dry; do
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --toggle-collect='dem::Simulation::advance()' --callgrind-out-file="$out/cg_$stage.out" \
    "$build/tools/run-stage" --scene "$src/drag/scene.toml" --stage $stage --in "$out/pack.h5" --out "$out/$stage.h5" --quiet 2>&1 | grep "refs"
done
callgrind_annotate --inclusive=yes "$out/cg_well.out" | grep -E "dem::void_fractions\(.*\) \[|FluidField::force"
