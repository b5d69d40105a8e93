#!/usr/bin/env bash
# [stage.sink] through run-stage (tests/data/sink.toml): particles are removed while the stage runs;
# a run on two threads equals one on one thread, and a run resumed with --restart from a periodic
# checkpoint taken while particles were being removed equals an uninterrupted run, checkpoint and
# sink log (OUT.sink.csv) both; the log's totals match the particles missing from the checkpoint.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
scene=$src/data/sink.toml
full_and_cut "$scene" drain 2000
grep "sink:" "$tmp/full.log"
cmp "$tmp/full.sink.csv" "$tmp/cut.sink.csv" || { echo "FAIL: the sink log on two threads differs from one"; exit 1; }
# The resumed run must find the interrupted run's partial log as it was then: keep its rows up to
# the checkpoint's step and a few after (an interrupted run wrote on past it).
mv "$tmp/mid.h5" "$tmp/cut.restart.h5"
cp "$tmp/cut.sink.csv" "$tmp/cut.sink.csv.partial"
rm "$tmp/cut.h5" "$tmp/cut.sink.csv"
"$py" - "$tmp/cut.restart.h5" "$tmp/full.h5" "$tmp/start.h5" <<'PY'
import sys, h5py
mid, full, start = (h5py.File(p, "r") for p in sys.argv[1:4])
part, total = mid["run/sink_count"][0], full["run/sink_count"][0]
assert 0 < part < total, f"checkpoint with {part} of {total} removed: not in the middle of draining"
n0, n1 = start["particles/id"].shape[0], full["particles/id"].shape[0]
assert n0 - n1 == total, f"{n0} - {n1} particles left, the sink counted {total}"
print(f"resumed from a checkpoint holding {part} of the {total} particles removed")
PY
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage drain --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 2000 --restart --quiet
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/cut.h5"
cmp "$tmp/full.sink.csv" "$tmp/cut.sink.csv" || { echo "FAIL: the resumed sink log differs"; exit 1; }
"$py" - "$tmp/full.sink.csv" "$tmp/full.h5" "$tmp/start.h5" <<'PY'
import sys, csv, h5py
import numpy as np
rows = list(csv.DictReader(open(sys.argv[1])))
full, start = h5py.File(sys.argv[2], "r"), h5py.File(sys.argv[3], "r")
assert int(rows[0]["removed_total"]) == 0 and int(rows[-1]["removed_total"]) == full["run/sink_count"][0]
gone = ~np.isin(start["particles/id"][:], full["particles/id"][:])
mass = np.sort(start["particles/mass"][:][gone])
logged = float(rows[-1]["removed_mass_kg"])
assert abs(logged - mass.sum()) <= 1e-12 * mass.sum(), (logged, mass.sum())
steps = [int(r["step"]) for r in rows]
assert steps == sorted(steps) and len(set(steps)) == len(steps), "rows out of order or twice"
print(f"{len(rows)} rows; {gone.sum()} particles, {logged:.6g} kg removed")
PY
echo "sink restart exact"
