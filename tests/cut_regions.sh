#!/usr/bin/env bash
# Cutting regions through the tools, checked with h5py against the analytic regions:
# - run-stage's remove action with an infinite vertical cylinder removes exactly the particles
#   whose centres (in the input checkpoint) lie within its radius of the axis;
# - gen-primary's [[generation.cut]] (a half-space, then a closed STL cube with inside = false)
#   leaves exactly the particles of the same settled set (same scene without the cuts: the same
#   bits) whose centres are below the plane and inside the cube.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/cut.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --threads 1 --quiet > /dev/null
"$bin/run-stage" --scene "$scene" --stage drill --in "$tmp/settled.h5" --out "$tmp/drilled.h5" --threads 1 --quiet 2> "$tmp/drill.log"
cat "$tmp/drill.log"
{ cat "$scene"; cat <<TOML

[[generation.cut]]
region = { type = "half_space", point = [0.0, 0.0, 0.005], normal = [0.0, 0.0, 1.0] }

[[generation.cut]]
region = { type = "mesh", file = "$src/data/cube.stl", scale = 0.0015, translate = [0.0025, 0.0025, -0.001] }
inside = false
TOML
} > "$tmp/cut.toml"
"$bin/gen-primary" --scene "$tmp/cut.toml" --out "$tmp/cut.h5" --threads 1 --quiet | tee "$tmp/cut.log"
"$py" - "$tmp/settled.h5" "$tmp/drilled.h5" "$tmp/cut.h5" "$tmp/drill.log" "$tmp/cut.log" <<'PY'
import re, sys
import h5py
import numpy as np
def load(path):
    f = h5py.File(path, "r")
    return f["/particles/id"][:], f["/particles/position"][:]
ids, x = load(sys.argv[1])
# Stage: remove the centres within 4 mm of the vertical axis through (0.01, 0.01).
inside = (x[:, 0] - 0.01) ** 2 + (x[:, 1] - 0.01) ** 2 <= 0.004 ** 2
drilled, _ = load(sys.argv[2])
assert 0 < inside.sum() < len(ids), "the hole should take some particles, not all"
assert set(drilled) == set(ids[~inside]), "run-stage removed other particles than those inside the cylinder"
assert "removed %d particles, %d remain" % (inside.sum(), len(drilled)) in open(sys.argv[4]).read()
print("drill: %d of %d particles inside the cylinder, exactly those removed" % (inside.sum(), len(ids)))
# gen-primary: the cuts in order: above z = 5 mm goes, then whatever is outside the cube
# [2.5, 17.5] x [2.5, 17.5] x [-1, 14] mm.
above = x[:, 2] >= 0.005
lo, hi = np.array([0.0025, 0.0025, -0.001]), np.array([0.0175, 0.0175, 0.014])
in_cube = np.all((x >= lo) & (x <= hi), axis=1)
keep = ~above & in_cube
cut_ids, cut_x = load(sys.argv[3])
assert 0 < keep.sum() < len(ids) and above.sum() > 0 and (~above & ~in_cube).sum() > 0, "each cut should take some particles"
assert list(cut_ids) == list(ids[keep]), "gen-primary kept other particles than those below the plane and inside the cube"
assert np.array_equal(cut_x, x[keep]), "the kept particles should be exactly where the uncut run left them"
log = open(sys.argv[5]).read()
assert "generation.cut[0] removed %d particles" % above.sum() in log, log
assert "generation.cut[1] removed %d particles, %d remain" % ((~above & ~in_cube).sum(), keep.sum()) in log, log
print("cuts: %d above the plane, then %d outside the cube removed; %d kept, as expected" % (above.sum(), (~above & ~in_cube).sum(), keep.sum()))
PY
