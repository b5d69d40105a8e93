#!/usr/bin/env bash
# [stage.fibres] through run-stage (tests/data/fibres.toml): fibres placed at the stage start and
# stretched until some break; a run resumed from a mid-stage periodic checkpoint on two threads
# gives the bits of an uninterrupted run on one (fibres, ties and broken flags included); the fibre
# frames open with VTK's own reader and match the checkpoint (tests/check_fibre_vtk.py); a damaged
# /fibres dataset is refused with its name; post-macro's stress holds the fibres' part.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
scene=$src/data/fibres.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/start.h5" --quiet
OMP_NUM_THREADS=1 "$bin/run-stage" --scene "$scene" --stage press --in "$tmp/start.h5" --out "$tmp/full.h5" --vtk "$tmp/vtk" 2> "$tmp/full.log"
cat "$tmp/full.log"
grep -q "stage press: placed 12 fibres" "$tmp/full.log" || { echo "FAIL: no fibre placement report"; exit 1; }

catch_checkpoint "$tmp/cut.restart.h5" "$tmp/mid.h5" -- env OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage press --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 3000 --quiet
cp "$tmp/mid.h5" "$tmp/cut.restart.h5"
rm "$tmp/cut.h5"
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage press --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 3000 --restart --quiet
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/cut.h5"
"$py" - "$tmp/full.h5" "$tmp/cut.h5" "$tmp/mid.h5" <<'PY'
import sys, h5py
import numpy as np
full, cut, mid = (h5py.File(p, "r") for p in sys.argv[1:4])
for name in ("first_tie", "area", "youngs_modulus", "tensile_strength", "tie_particle", "tie_offset", "segment_rest_length", "segment_broken"):
    a, b = full["fibres/" + name][()], cut["fibres/" + name][()]
    assert a.shape == b.shape and a.tobytes() == b.tobytes(), f"/fibres/{name} differs after the restart"
broken_mid, broken_end = mid["fibres/segment_broken"][()].sum(), full["fibres/segment_broken"][()].sum()
n = len(full["fibres/segment_broken"])
print(f"fibres: {n} segments, {broken_mid} broken at the periodic checkpoint, {broken_end} at the end")
assert broken_end > 0 and broken_end < n, "the test needs some segments broken and some intact"
PY
"$py" "$src/check_fibre_vtk.py" "$tmp/vtk" press "$tmp/full.h5"

# Damaged fibre datasets (edited with h5py, the seal made again so that the reader's own checks
# meet them) are refused, each naming its dataset, with exit 4.
for variant in "segment_broken:7" "segment_rest_length:-1" "tie_particle:999999" "first_tie:1" "tie_offset:nan" "youngs_modulus:0"; do
  name=${variant%%:*} value=${variant#*:}
  cp "$tmp/full.h5" "$tmp/bad.h5"
  "$py" - "$tmp/bad.h5" "$name" "$value" "$src" <<'PY'
import sys, h5py
sys.path.insert(0, sys.argv[4])
from damaged_checkpoints import reseal
path, name, value = sys.argv[1:4]
with h5py.File(path, "r+") as f:
    d = f["fibres/" + name]
    if d.ndim == 2:
        d[0, 0] = float(value)
    else:
        d[0] = float(value) if d.dtype.kind == "f" else int(value)
reseal(path)
PY
  rc=0
  "$bin/run-stage" --scene "$scene" --stage press --in "$tmp/bad.h5" --out "$tmp/n.h5" 2> "$tmp/bad.log" || rc=$?
  [ $rc -eq 4 ] || { cat "$tmp/bad.log"; echo "FAIL: /fibres/$name = $value: exit $rc, not 4"; exit 1; }
  grep -q "/fibres/$name" "$tmp/bad.log" || { cat "$tmp/bad.log"; echo "FAIL: the message does not name /fibres/$name"; exit 1; }
  echo "/fibres/$name = $value refused: $(head -c 300 "$tmp/bad.log")"
done
echo "fibre stage: ok"
