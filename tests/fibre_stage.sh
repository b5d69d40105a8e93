#!/usr/bin/env bash
# [stage.fibres] through run-stage (tests/data/fibres.toml): fibres placed at the stage start and
# stretched until some break; a run resumed from a mid-stage periodic checkpoint on two threads
# gives the bits of an uninterrupted run on one (fibres, ties and broken flags included); the fibre
# frames open with VTK's own reader and match the checkpoint (tests/check_fibre_vtk.py); a damaged
# /fibres dataset is refused with its name; post-macro's stress holds the fibres' part, in the box
# averages (eq. P64) and on the grid (eq. P65), against the fibres' T e (x) l summed here from the
# checkpoint (see the end).
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
# post-macro end to end on the stretched fibres: the same state with every segment marked broken
# (no fibre force, the contacts unchanged) is subtracted, which leaves the fibres' part. It must
# equal sum T e (x) l over the segments, computed here from the checkpoint (tie points = particle
# position + offset, T = E A / L0 (L - L0) when stretched and below sigma_t A, eq. P60-P62): the box average times
# the box's volume to round-off (1e-9 of the total: the sums run in other orders; plus the CSV's
# 10 significant digits of the whole stresses, whose contact part cancels), and the grid
# field summed over its nodes times h^3 (h = w/2) within 1e-4: the nodes sample the smooth kernel,
# measured within 1e-6 here.
cp "$tmp/full.h5" "$tmp/slack.h5"
"$py" - "$tmp/slack.h5" "$src" <<'PY'
import sys, h5py
sys.path.insert(0, sys.argv[2])
from damaged_checkpoints import reseal
with h5py.File(sys.argv[1], "r+") as f:
    f["fibres/segment_broken"][...] = 1
reseal(sys.argv[1])
PY
region=box:-0.012,-0.012,-0.012,0.032,0.032,0.052  # the box and the kernel's reach (c = 3.46 w) around it
for state in full slack; do
  "$bin/post-macro" --in "$tmp/$state.h5" --grid "$tmp/$state.vti" --cell 0.001 --width 0.002 --region $region \
    --average-csv "$tmp/$state.avg.csv" --quiet
done
"$py" - "$tmp" "$region" <<'PY'
import sys, h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
d = sys.argv[1]
lo_hi = [float(v) for v in sys.argv[2].split(":")[1].split(",")]
volume = np.prod(np.array(lo_hi[3:]) - np.array(lo_hi[:3]))
with h5py.File(f"{d}/full.h5", "r") as h:
    first, tie_id, offset = h["fibres/first_tie"][()], h["fibres/tie_particle"][()], h["fibres/tie_offset"][()]
    area, modulus, strength = h["fibres/area"][()], h["fibres/youngs_modulus"][()], h["fibres/tensile_strength"][()]
    rest, broken = h["fibres/segment_rest_length"][()], h["fibres/segment_broken"][()]
    pos = dict(zip(h["particles/id"][()], h["particles/position"][()]))
total, s, stretched = np.zeros((3, 3)), 0, 0
for f in range(len(first) - 1):
    for t in range(first[f], first[f + 1] - 1):
        a, b = pos[tie_id[t]] + offset[t], pos[tie_id[t + 1]] + offset[t + 1]
        length = np.linalg.norm(b - a)
        tension = modulus[f] * area[f] / rest[s] * (length - rest[s])
        if not broken[s] and length > rest[s] and tension <= strength[f] * area[f]:  # beyond it: breaks at the next step
            total += np.outer(tension * (b - a) / length, pos[tie_id[t + 1]] - pos[tie_id[t]])
            stretched += 1
        s += 1
assert stretched > 0, "no stretched fibre: the check checks nothing"
def average(path):
    lines = [l for l in open(path) if not l.startswith("#")]
    head, row = lines[0].strip().split(","), [float(v) for v in lines[1].split(",")]
    return np.array([row[head.index(c)] for c in ("sxx", "sxy", "sxz", "syx", "syy", "syz", "szx", "szy", "szz")]).reshape(3, 3)
def grid_sum(path):
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    h = img.GetSpacing()[0]
    return vtk_to_numpy(img.GetPointData().GetArray("stress")).reshape(-1, 3, 3).sum(axis=0) * h ** 3
scale = np.abs(total).max()
full, slack = average(f"{d}/full.avg.csv"), average(f"{d}/slack.avg.csv")
# The CSV holds 10 significant digits of each whole stress, contacts included: half a unit of the
# last, of both, on top of the 1e-9.
box_tol = 1e-9 * scale + ((np.abs(full) + np.abs(slack)) * 5e-10 * volume).max()
box_err = np.abs((full - slack) * volume - total).max()
grid_err = np.abs(grid_sum(f"{d}/full.vti") - grid_sum(f"{d}/slack.vti") - total).max() / scale
print(f"post-macro, fibres' part of {stretched} stretched segments (largest component {scale:.4g} N m): "
      f"box average x volume within {box_err:.3g} N m (allowed {box_tol:.3g}), grid integral within {grid_err:.2e} of sum T e (x) l")
assert box_err < box_tol, "the box average's fibre part is not sum T e (x) l / V"
assert grid_err < 1e-4, "the grid's fibre part does not integrate to sum T e (x) l"
PY
echo "fibre stage: ok"
