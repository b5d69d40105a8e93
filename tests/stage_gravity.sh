#!/usr/bin/env bash
# A stage's own gravity: the settled bed of tests/data/small.toml carries its weight on the walls,
# M g, under g = 20 m/s^2 in a stage that sets it, and under the scene's 9.81 m/s^2 again in the
# next stage, which does not. The vertical force on all walls together (the side walls hold part
# of the weight by friction), averaged over the stage's second half, once the bed has settled to
# the new load (restitution 0.3: a few contact times), within 2 % of M g (the bed's vertical
# oscillation about rest averages out over many periods).
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$tmp/scene.toml
cp "$src/data/small.toml" "$scene"
cat >> "$scene" <<'TOML'

[[stage]]
name = "heavy"
duration = 0.05
gravity = [0.0, 0.0, -20.0]

[[stage]]
name = "back"
duration = 0.05
TOML
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null || exit 1
"$bin/run-stage" --scene "$scene" --stage heavy --in "$tmp/settled.h5" --out "$tmp/heavy.h5" --wall-forces "$tmp/heavy.csv" \
  --wall-forces-every 20 --quiet > /dev/null 2>&1 || exit 1
"$bin/run-stage" --scene "$scene" --stage back --in "$tmp/heavy.h5" --out "$tmp/back.h5" --wall-forces "$tmp/back.csv" \
  --wall-forces-every 20 --quiet > /dev/null 2>&1 || exit 1
"$py" - "$tmp/settled.h5" "$tmp/heavy.csv" "$tmp/back.csv" <<'PY' || exit 1
import csv
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    weight_per_g = (2500 * 4 / 3 * np.pi * f["/particles/radius"][:] ** 3).sum()  # one material, glass
fail = False
for path, g in ((sys.argv[2], 20.0), (sys.argv[3], 9.81)):
    total = {}
    for r in csv.DictReader(open(path)):
        total[float(r["time_s"])] = total.get(float(r["time_s"]), 0.0) + float(r["fz_N"])
    t = np.array(sorted(total))
    fz = np.array([total[x] for x in t])
    late = fz[t >= 0.5 * t.max()]
    ratio = -late.mean() / (weight_per_g * g)
    print(f"{path.split('/')[-1]}: vertical wall force / (M g) = {ratio:.4f} for g = {g} m/s^2 ({len(late)} samples)")
    if abs(ratio - 1) > 0.02:
        fail = True
sys.exit(1 if fail else 0)
PY
