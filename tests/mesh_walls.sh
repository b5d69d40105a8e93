#!/bin/bash
# Mesh walls through the tools: gen-primary pours spheres through a cone-mesh hopper onto a floor
# of 2 x 2 quads beside STL walls (tests/data/mesh_walls.toml), run-stage lifts the hopper (a
# wall group) and writes VTK. Checks: every element is in the checkpoint under its NAME.K name,
# and no sphere fell through the meshed floor (centres stay above half a radius). Then: an STL file
# edited while a run is interrupted is refused by --restart (the scene text is the same, the
# walls it builds are not), and restored it is accepted again.
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

# An interrupted run (kill -9 after its first periodic checkpoints), the deflector's STL edited
# (one vertex 1 mm lower), --restart: refused with exit 3; the file restored: it resumes.
mkdir "$tmp/edit"
cp "$data/mesh_walls.toml" "$data/deflector.stl" "$data/baffle.stl" "$tmp/edit/"
sed -i 's/^duration = 0.02$/duration = 100.0/' "$tmp/edit/mesh_walls.toml"
grep -q '^duration = 100.0$' "$tmp/edit/mesh_walls.toml"
args=(--scene "$tmp/edit/mesh_walls.toml" --stage lift --in "$tmp/p.h5" --out "$tmp/edit/l.h5" --checkpoint-every 20 --restart --quiet)
"$bin/run-stage" "${args[@]}" & pid=$!
for _ in $(seq 100); do [ -e "$tmp/edit/l.restart.h5" ] && break; sleep 0.1; done
sleep 0.3; kill -9 $pid; wait $pid 2> /dev/null || true
test -e "$tmp/edit/l.restart.h5"
cp "$tmp/edit/deflector.stl" "$tmp/edit/deflector.orig"
sed -i '0,/vertex 0 15 0/s//vertex 0 15 -1/' "$tmp/edit/deflector.stl"
! cmp -s "$tmp/edit/deflector.stl" "$tmp/edit/deflector.orig"
rc=0; timeout 5 "$bin/run-stage" "${args[@]}" > "$tmp/edit/out" 2>&1 || rc=$?
if [ $rc -ne 3 ] || ! grep -q "l.restart.h5 was written with other walls: the walls .*mesh_walls.toml builds differ" "$tmp/edit/out"; then
  echo "FAIL an edited STL file was not refused by --restart (exit $rc):"; cat "$tmp/edit/out"; exit 1
fi
echo "ok   an edited STL file is refused by --restart"
cp "$tmp/edit/deflector.orig" "$tmp/edit/deflector.stl"
rc=0; timeout 3 "$bin/run-stage" "${args[@]}" > "$tmp/edit/out" 2>&1 || rc=$?
# (it resumes and runs on until the timeout stops it: 124, not the refusal's 3)
if [ $rc -ne 124 ]; then echo "FAIL the restored file was not accepted (exit $rc):"; cat "$tmp/edit/out"; exit 1; fi
echo "ok   the restored STL file is accepted"
