#!/usr/bin/env bash
# [[stage.insert]] through run-stage (tests/data/insert.toml): a run resumed with --restart from a
# periodic checkpoint taken in the middle of pouring, on two threads, gives the same bits as an
# uninterrupted run on one; ids continue after the largest present; the
# mass poured is mass_rate x duration within 2 % (one particle is about 1 %); no sphere overlaps
# another by more than 1 % of its radius at the end (they were placed apart and settle under gravity).
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
scene=$src/data/insert.toml
# A periodic checkpoint taken in the middle of pouring (each is renamed into place whole, so a
# copy of one is complete), resumed with --restart after the run that wrote it has finished.
full_and_cut "$scene" pour 3000
grep "insert\[0\]" "$tmp/full.log"
mv "$tmp/mid.h5" "$tmp/cut.restart.h5"
rm "$tmp/cut.h5"
"$py" - "$tmp/cut.restart.h5" "$tmp/full.h5" <<'PY'
import sys, h5py
part, full = (h5py.File(p, "r")["run/insert_count"][0] for p in sys.argv[1:3])
assert 0 < part < full, f"checkpoint with {part} of {full} inserted: not in the middle of pouring"
print(f"resumed from a checkpoint holding {part} of the {full} particles inserted")
PY
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage pour --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 3000 --restart --quiet
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/cut.h5"

"$py" - "$tmp/full.h5" "$tmp/start.h5" <<'PY'
import sys, h5py
import numpy as np
f, s = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
ids, old = f["particles/id"][:], s["particles/id"][:]
new = np.sort(ids[~np.isin(ids, old)])
n = f["run/insert_count"][0]
assert len(np.unique(ids)) == len(ids), "ids not unique"
assert len(new) == n and np.array_equal(new, np.arange(old.max() + 1, old.max() + 1 + n)), "new ids do not continue the old ones"
mass = f["particles/mass"][:][np.isin(ids, new)].sum()
asked = 0.04 * 0.08
print(f"poured {n} particles, {mass:.6g} kg against {asked:.6g} kg asked ({100 * (mass / asked - 1):+.2f} %)")
assert abs(mass / asked - 1) < 0.02, "mass rate not kept within 2 %"
x, a = f["particles/position"][:], f["particles/radius"][:]
gap = np.linalg.norm(x[:, None] - x[None, :], axis=2) - (a[:, None] + a[None, :])
np.fill_diagonal(gap, 1)
worst = (-gap / np.minimum(a[:, None], a[None, :])).max()
assert worst < 0.01, f"overlap of {worst:.3g} radii"
PY
echo "insertion restart exact"
