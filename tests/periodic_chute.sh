#!/usr/bin/env bash
# Periodic boundaries and held particles through the tools (tests/data/periodic_chute.toml):
# gen-primary, run-stage with a `fix` action, post-macro and the VTK frames, checked with h5py:
# - exactly the particles whose centre is in the fix region are held: their positions, to the bit,
#   and zero velocities at the end; run-stage reports how many;
# - every position stays inside the period along x and y; some particles crossed it (image counts);
# - the free particles moved down the slope: mean unwrapped displacement along x > 1 mm (gravity's
#   slope component is 4.9 m/s^2 for 0.05 s), and post-macro's displacement (from the reference
#   checkpoint, unwrapped) agrees with h5py's to 1e-12 m; the VTK marks the held particles;
# - no force-chain line is longer than a diameter (contacts across the boundary go to the image).
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/periodic_chute.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/poured.h5" --threads 1 --quiet > /dev/null
"$bin/run-stage" --scene "$scene" --stage flow --in "$tmp/poured.h5" --out "$tmp/flow.h5" --vtk "$tmp/vtk" --threads 2 --quiet 2> "$tmp/flow.log"
cat "$tmp/flow.log"
"$bin/post-macro" --reference "$tmp/poured.h5" --in "$tmp/flow.h5" --vtk "$tmp/post.vtu" --chains "$tmp/chains.vtp" --threads 1 > "$tmp/post.log"
ls "$tmp/vtk" | grep -q "particles" || { echo "no VTK frames"; exit 1; }
"$py" - "$tmp/poured.h5" "$tmp/flow.h5" "$tmp/flow.log" "$tmp/post.vtu" "$tmp/chains.vtp" <<'PY'
import sys
import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
assert list(b["/state/periodic"][:]) == [1, 1, 0]
lo, hi = b["/state/periodic_lo"][0], b["/state/periodic_hi"][0]
assert np.allclose(hi - lo, [0.02, 0.01, 0]), (lo, hi)
ida, xa = a["/particles/id"][:], a["/particles/position"][:]
idb, xb, vb = b["/particles/id"][:], b["/particles/position"][:], b["/particles/velocity"][:]
assert list(ida) == list(idb)
held = xa[:, 2] <= 0.0015
fixed = b["/particles/fixed"][:] == 1
assert held.sum() > 5 and np.array_equal(held, fixed), (held.sum(), fixed.sum())
assert ("fixed %d particles" % held.sum()) in open(sys.argv[3]).read()
assert np.array_equal(xa[held], xb[held]), "held particles must not move"
assert not vb[held].any(), "held particles have zero velocity"
assert np.all((xb[:, :2] >= lo[:2]) & (xb[:, :2] < hi[:2])), "positions stay inside the period"
image = b["/particles/image"][:]
assert np.abs(image).sum() > 0, "some particle must have crossed the periodic boundary"
ua = xa + a["/particles/image"][:] * (hi - lo)
ub = xb + image * (hi - lo)
u = ub - ua
mean_ux = u[~held, 0].mean()
assert mean_ux > 0.001, "the free particles should flow down the slope (+x): mean ux = %g m" % mean_ux
r = vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[4]); r.Update()
u_post = vtk_to_numpy(r.GetOutput().GetPointData().GetArray("displacement"))
assert np.allclose(u_post, u, rtol=0, atol=1e-12), "post-macro's displacement is the unwrapped one"
assert vtk_to_numpy(r.GetOutput().GetPointData().GetArray("fixed")).sum() == held.sum()
# Force chains: a contact across the boundary is drawn to the neighbour's image, never across the slab.
c = vtkXMLPolyDataReader(); c.SetFileName(sys.argv[5]); c.Update()
pts = vtk_to_numpy(c.GetOutput().GetPoints().GetData())
lines = vtk_to_numpy(c.GetOutput().GetLines().GetConnectivityArray()).reshape(-1, 2)
longest = np.linalg.norm(pts[lines[:, 1]] - pts[lines[:, 0]], axis=1).max()
assert longest <= 0.002 + 1e-12, "a force-chain line spans %g m, more than a diameter" % longest
print("held %d, free %d, crossings %d, mean downslope displacement %.3g mm" % (held.sum(), (~held).sum(), np.abs(image).sum(), 1e3 * mean_ux))
PY
