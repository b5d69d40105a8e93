#!/bin/bash
# Mesh walls through the tools: gen-primary pours spheres through a cone-mesh hopper onto a floor
# of 2 x 2 quads beside STL walls (tests/data/mesh_walls.toml), run-stage lifts the hopper (a
# wall group) and writes VTK. Checks: every element is in the checkpoint under its NAME.K name,
# and no sphere fell through the meshed floor (centres stay above half a radius).
set -euo pipefail
bin=$1 data=$2 py=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/gen-primary" --scene "$data/mesh_walls.toml" --out "$tmp/p.h5" --quiet
"$bin/run-stage" --scene "$data/mesh_walls.toml" --stage lift --in "$tmp/p.h5" --out "$tmp/l.h5" --vtk "$tmp/vtk" --quiet
test -s "$tmp/vtk/lift/walls_000000.vtp"
"$py" - "$tmp/l.h5" <<'PY'
import sys
import h5py
f = h5py.File(sys.argv[1], "r")
names = [n.decode() if isinstance(n, bytes) else n for n in f["/walls/name"][:]]
want = ["floor.%d" % k for k in range(4)] + ["hopper.%d" % k for k in range(32)] + \
       ["deflector.%d" % k for k in range(4)] + ["baffle.%d" % k for k in range(2)]
assert names == want, names
z = f["/particles/position"][:, 2]
r = f["/particles/radius"][:]
assert len(z) == 150 and (z > 0.5 * r).all(), "a sphere fell through the floor: min z = %g" % z.min()
print("mesh walls: %d elements, %d spheres above the floor" % (len(names), len(z)))
PY
