#!/usr/bin/env bash
# Speed against error for the sand-production case's production phase (issue 32).
# Small (the default), on the small version (small.toml): the same drilled slab produced for its
# 3 ms with the time step (FRAC, the fraction of the critical step, docs/physics.md eq. P5: 0.2,
# 0.1 and 0.05; run-stage refuses more than 0.2 unless forced) and the void fraction's support
# (void_cutoff, docs/physics.md "Local void fraction") changed one at a time from the case's own
# (FRAC 0.2, void_cutoff 0.033 m = 3 mean diameters).
# Full (`full DIR`), on the full case's drilled slab (DIR/drilled.h5 and DIR/cemented.h5, from
# `make -f Makefile.cases sand-production-drill`): the first tenth of the production (3.4 ms)
# with the time step 5.08e-8 s (the thesis's), half and 1.5 times that, and void_cutoff 0.033,
# 0.022 and 0.044 m.
# For each run: the produced grains and mass, the hoop and radial stress in the bins within 2a and
# beyond 2a (post-macro, scripts/well_report.py), the broken-bond fraction, and the stepping wall
# time and particle-steps per second.
# Writes OUT/speed_error.csv and OUT/speed_error.md (the README's table).
# Usage: bash workflows/sand-production/speed_error.sh [BUILD] [OUT] [full DIR]
#   (small: about 3 minutes on 2 cores; full: about 30 minutes)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${1:-build}/tools out=${2:-out/sand-production/speed_error}
py=/usr/bin/python3
case_dir=workflows/sand-production
mkdir -p "$out"
q=--quiet
mode=${3:-small}
if [ "$mode" = full ]; then
  dir=${4:?full: give the directory holding drilled.h5 and cemented.h5 of the full case}
  scene=$case_dir/scene.toml drilled=$dir/drilled.h5 cemented=$dir/cemented.h5
  well=(--centre 0.5,0.5 --radius 0.09 --sigma0 18e6 --outer 0.48 --bin 0.02)  # case.mk's SAND_WELL
  step_column=time_step_s step_line='^time_step = 5.08e-8 .*' step_key=time_step
  runs=("5.08e-8 0.033" "2.54e-8 0.033" "7.62e-8 0.033" "5.08e-8 0.022" "5.08e-8 0.044")
  shorten=(-e 's/^duration = 0.034036 .*/duration = 0.0034036/')
else
  scene=$case_dir/small.toml drilled=$out/drilled.h5 cemented=$out/cemented.h5
  well=(--centre 0.14,0.14 --radius 0.035 --sigma0 18e6 --outer 0.126 --bin 0.014)
  step_column=frac step_line='^frac = 0.2$' step_key=frac
  runs=("0.2 0.033" "0.1 0.033" "0.05 0.033" "0.2 0.022" "0.2 0.044")
  shorten=()
fi
# The small chain up to the drilled slab, once (tests/sand_production_small.sh's).
if [ "$mode" != full ] && [ ! -e "$out/drilled.h5" ]; then
  "$bin/gen-primary" --scene $case_dir/small-generate.toml --out "$out/settled.h5" $q
  "$bin/compact" --scene $case_dir/small-generate.toml --in "$out/settled.h5" --out "$out/compacted.h5" $q
  "$bin/run-stage" --scene $case_dir/small.toml --stage load --in "$out/compacted.h5" --out "$out/loaded.h5" $q
  "$bin/run-stage" --scene $case_dir/small.toml --stage cement --in "$out/loaded.h5" --out "$out/cemented.h5" $q
  "$bin/run-stage" --scene $case_dir/small.toml --stage drill --in "$out/cemented.h5" --out "$out/drilled.h5" $q
fi
echo "$step_column,void_cutoff_m,steps,stepping_s,particle_steps_per_s,produced_grains,produced_kg,stt_near_MPa,srr_near_MPa,stt_far_MPa,srr_far_MPa,broken_fraction" > "$out/speed_error.csv"
for run in "${runs[@]}"; do
  read -r step cutoff <<< "$run"
  name=${step_key}${step}_cut${cutoff}
  sed "${shorten[@]}" -e "s/$step_line/$step_key = $step/" -e "s/^void_cutoff = 0.033 .*/void_cutoff = $cutoff/" "$scene" > "$out/$name.toml"
  grep -q "^$step_key = $step$" "$out/$name.toml" && grep -q "^void_cutoff = $cutoff$" "$out/$name.toml" ||
    { echo "$scene's $step_key or void_cutoff was not found"; exit 1; }
  "$bin/run-stage" --scene "$out/$name.toml" --stage produce --in "$drilled" --out "$out/$name.h5" 2> "$out/$name.log" > /dev/null
  "$bin/post-macro" --in "$out/$name.h5" --reference "$cemented" --vtk "$out/$name.vtu" $q
  "$py" scripts/well_report.py --stress "$out/$name.vtu" --bonds-made "$cemented" --bonds-now "$out/$name.h5" \
    "${well[@]}" --prefix "$out/$name" > /dev/null
  "$py" - "$out" "$name" "$step" "$cutoff" >> "$out/speed_error.csv" <<'PY'
import csv, re, sys
out, name, step, cutoff = sys.argv[1:]
log = open(f"{out}/{name}.log").read()
m = re.search(r"stage produce done: (\d+) steps in ([0-9.]+) s wall time, ([0-9.e+]+) particle-steps/s", log)
sink = list(csv.DictReader(open(f"{out}/{name}.sink.csv")))[-1]
rows = list(csv.DictReader(open(f"{out}/{name}_kirsch.csv")))
mean = lambda sel, k: sum(float(r[k]) for r in sel) / len(sel) / 1e6
near = [r for r in rows if float(r["r_over_a"]) < 2]
far = [r for r in rows if float(r["r_over_a"]) >= 2]
bonds = list(csv.DictReader(open(f"{out}/{name}_bonds.csv")))
broken = sum(int(r["broken"]) for r in bonds) / max(1, sum(int(r["bonds"]) for r in bonds))
print(f"{step},{cutoff},{m[1]},{m[2]},{m[3]},{sink['removed_total']},{float(sink['removed_mass_kg']):.4g},"
      f"{mean(near, 'stt_Pa'):.2f},{mean(near, 'srr_Pa'):.2f},{mean(far, 'stt_Pa'):.2f},{mean(far, 'srr_Pa'):.2f},{broken:.4f}")
PY
done
"$py" - "$out" "$step_column" > "$out/speed_error.md" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/speed_error.csv")))
step = sys.argv[2]
print(f"| {'FRAC' if step == 'frac' else 'Δt [s]'} | void_cutoff [m] | steps | stepping [s] | particle-steps/s | produced grains | produced [g] | σθθ / σrr, r < 2a [MPa] | σθθ / σrr, r ≥ 2a [MPa] | bonds broken |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r[step]} | {r['void_cutoff_m']} | {r['steps']} | {r['stepping_s']} | {float(r['particle_steps_per_s']):.3g} | {r['produced_grains']} | "
          f"{1000 * float(r['produced_kg']):.1f} | {r['stt_near_MPa']} / {r['srr_near_MPa']} | {r['stt_far_MPa']} / {r['srr_far_MPa']} | {r['broken_fraction']} |")
PY
cat "$out/speed_error.md"
