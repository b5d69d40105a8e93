#!/usr/bin/env bash
# post-macro --fragments end to end: the settled bed of tests/data/small.toml, bonded by a stage
# that then removes a layer through its middle (two large pieces at least); the fragments the
# tool writes must be the groups a separate union-find (Python, over the checkpoint's /contacts)
# finds, with the grading column consistent, and the particles' VTU must carry each particle's
# fragment.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$tmp/scene.toml
cp "$src/data/small.toml" "$scene"
cat >> "$scene" <<'TOML'

[[stage]]
name = "glue"
duration = 0.002
output_every = 0.002

[[stage.action]]
type = "bond"

[[stage.action]]
type = "remove"
region = { type = "box", min = [0.0, 0.0, 0.004], max = [0.02, 0.02, 0.0085] }
TOML
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null || exit 1
"$bin/run-stage" --scene "$scene" --stage glue --in "$tmp/settled.h5" --out "$tmp/glued.h5" --quiet > /dev/null 2>&1 || exit 1
"$bin/post-macro" --in "$tmp/glued.h5" --fragments "$tmp/fragments.csv" --vtk "$tmp/p.vtu" > "$tmp/log" || { cat "$tmp/log"; exit 1; }
grep -q "fragments (.* intact bonds); the largest holds" "$tmp/log" || { echo "no fragment summary:"; cat "$tmp/log"; exit 1; }
"$py" - "$tmp/glued.h5" "$tmp/fragments.csv" "$tmp/p.vtu" <<'PY' || exit 1
import sys
import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

h5, csv, vtu = sys.argv[1:]
with h5py.File(h5, "r") as f:
    ids = f["/particles/id"][:]
    radius = f["/particles/radius"][:]
    pairs = f["/contacts/pair_ids"][:]
    bonded = f["/contacts/pair_bonded"][:]
index = {int(i): k for k, i in enumerate(ids)}
parent = list(range(len(ids)))
def root(k):
    while parent[k] != k:
        parent[k] = parent[parent[k]]
        k = parent[k]
    return k
n_bonds = 0
for (a, b), bond in zip(pairs, bonded):
    if bond:
        n_bonds += 1
        ra, rb = root(index[int(a)]), root(index[int(b)])
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
groups = {}
for k in range(len(ids)):
    groups.setdefault(root(k), []).append(k)
sizes = sorted((len(g) for g in groups.values()), reverse=True)
rows = np.loadtxt(csv, delimiter=",", comments="#", skiprows=2, ndmin=2)
header = open(csv).read().splitlines()[1].split(",")
col = {name: i for i, name in enumerate(header)}
fail = []
if n_bonds == 0:
    fail.append("the bond stage bonded nothing: the test checks nothing")
if sum(1 for s in sizes if s > 1) < 2:
    fail.append(f"fragment sizes {sizes}: two bonded pieces expected either side of the removed layer")
if len(rows) != len(groups):
    fail.append(f"{len(rows)} fragments written, {len(groups)} found by the checker")
if sorted(rows[:, col["particles"]].astype(int).tolist(), reverse=True) != sizes:
    fail.append("fragment sizes differ from the checker's")
if rows[:, col["particles"]].sum() != len(ids):
    fail.append("fragments do not hold every particle once")
m = rows[:, col["mass"]]
if np.any(np.diff(m) > 0):
    fail.append("not sorted largest mass first")
d = rows[:, col["equivalent_diameter"]]
# One material placed: mass = 2500 kg/m^3 times the fragment's volume pi d^3 / 6.
if np.max(np.abs(m / (2500 * np.pi * d**3 / 6) - 1)) > 1e-9:
    fail.append("mass and equivalent diameter disagree")
if abs(m.sum() / (2500 * (4 / 3 * np.pi * radius**3).sum()) - 1) > 1e-9:
    fail.append("the fragments' mass is not the particles'")
passing = rows[:, col["mass_passing"]]
order = np.argsort(d, kind="stable")
if abs(passing.max() - 1) > 1e-12:
    fail.append(f"mass_passing ends at {passing.max()}, not 1")
if np.any(np.diff(passing[order]) < -1e-15):
    fail.append("mass_passing falls as the diameter grows")
r = vtkXMLUnstructuredGridReader(); r.SetFileName(vtu); r.Update()
pd = r.GetOutput().GetPointData()
frag = vtk_to_numpy(pd.GetArray("fragment")).astype(int)
fsize = vtk_to_numpy(pd.GetArray("fragment_particles")).astype(int)
if np.any(rows[frag, col["particles"]].astype(int) != fsize):
    fail.append("fragment_particles in the VTU differ from the CSV row of the particle's fragment")
print(f"fragments: {len(groups)} for {len(ids)} particles and {n_bonds} bonds; largest {sizes[0]}")
if fail:
    print("\n".join(fail))
    sys.exit(1)
PY
"$py" "$src/../scripts/plot_fragments.py" "$tmp/fragments.csv" "$tmp/fragments.png" && [ -s "$tmp/fragments.png" ] \
  || { echo "plot_fragments.py drew nothing"; exit 1; }
