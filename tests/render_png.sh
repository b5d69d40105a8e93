#!/usr/bin/env bash
# dem-render on a tiny scene: three spheres of radius 0.1 m on the x axis at x = -1, 0, 1 with
# speeds 0, 2.5 and 5 m/s, a fourth (5 m/s) at y = 0.5 off the cut plane y = 0. Rendered with the
# colour range 0-5 m/s (blue to red through green), seen from -y (x to the right, z up):
# - the PNG has the size asked and is not blank (the spheres cover part of the white background);
# - the left third holds blue pixels and no red, the right third red and no blue (the spheres
#   coloured by their own speed, where the camera puts them);
# - the cut through y = 0 still shows the three spheres on the axis (blue left), and the series
#   (.pvd) form picks the frame asked;
# - without an X display it fails with exit 4 and says to use xvfb-run.
# Needs xvfb-run (Debian package xvfb): without it the test fails and says so.
set -euo pipefail
bin=$1 py=$2
command -v xvfb-run > /dev/null || { echo "FAIL: xvfb-run is missing: install the Debian package xvfb (scripts/bootstrap.sh does)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$py" - "$tmp" <<'PY'
import sys
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_VERTEX
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

d = sys.argv[1]
x = np.array([[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.5, 0.0]])
speed = np.array([0.0, 2.5, 5.0, 5.0])
for k, shift in enumerate((0.0, 10.0)):  # frame 1 is moved away: picking frame 0 matters
    g = vtkUnstructuredGrid()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(x + [0.0, 0.0, shift], deep=True))
    g.SetPoints(pts)
    for i in range(len(x)):
        g.InsertNextCell(VTK_VERTEX, 1, [i])
    r = numpy_to_vtk(np.full(len(x), 0.1), deep=True); r.SetName("radius")
    v = numpy_to_vtk(np.stack([speed, 0 * speed, 0 * speed], axis=1), deep=True); v.SetName("velocity")
    g.GetPointData().AddArray(r); g.GetPointData().AddArray(v)
    w = vtkXMLUnstructuredGridWriter(); w.SetFileName(f"{d}/f{k}.vtu"); w.SetInputData(g); w.Write()
open(f"{d}/s.pvd", "w").write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                              '<DataSet timestep="0" group="" part="0" file="f0.vtu"/>\n'
                              '<DataSet timestep="0.5" group="" part="0" file="f1.vtu"/>\n</Collection>\n</VTKFile>\n')
PY

common=(--range 0,5 --size 300,200 --box=-1.2,-0.2,-0.2,1.2,0.2,0.2)
xvfb-run -a "$bin/dem-render" --in "$tmp/f0.vtu" --direction 0,-1,0 "${common[@]}" --quiet --out "$tmp/p.png"
xvfb-run -a "$bin/dem-render" --in "$tmp/s.pvd" --time 0.1 --view cut --point 0,0,0 --normal 0,-1,0 "${common[@]}" \
  --out "$tmp/c.png" | tee "$tmp/cut.log"
grep -q "f0.vtu (t = 0 s): 3 spheres" "$tmp/cut.log" || { echo "FAIL: the cut did not draw the 3 spheres of frame 0 it crosses"; exit 1; }
set +e
env -u DISPLAY "$bin/dem-render" --in "$tmp/f0.vtu" --out "$tmp/x.png" 2> "$tmp/err"
rc=$?
set -e
[ $rc = 4 ] && grep -q xvfb-run "$tmp/err" || { echo "FAIL: without a display: exit $rc, $(cat "$tmp/err")"; exit 1; }
[ ! -e "$tmp/x.png" ] || { echo "FAIL: a PNG was written without a display"; exit 1; }

"$py" - "$tmp/p.png" "$tmp/c.png" <<'PY'
import sys
import matplotlib.image as mpimg
import numpy as np
fail = []
for path in sys.argv[1:]:
    img = mpimg.imread(path)[:, :, :3]
    if img.shape[:2] != (200, 300):
        fail.append(f"{path}: {img.shape[1]}x{img.shape[0]} pixels, 300x200 asked")
        continue
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    blue = (b > r + 0.3) & (b > g + 0.1)
    red = (r > b + 0.3) & (r > g + 0.3)
    coloured = blue | red | ((g > r + 0.2) & (g > b + 0.2))
    left, right = slice(0, 100), slice(200, 260)  # the colour bar stands right of 90 % of the width
    counts = dict(coloured=int(coloured.sum()), blue_left=int(blue[:, left].sum()), red_left=int(red[:, left].sum()),
                  red_right=int(red[:, right].sum()), blue_right=int(blue[:, right].sum()))
    print(path, counts)
    # A sphere of radius 0.1 in a 2.4 m wide frame 300 pixels across: about 12 pixels wide, ~100 pixels.
    if counts["coloured"] < 100:
        fail.append(f"{path}: blank or nearly ({counts['coloured']} coloured pixels)")
    if counts["blue_left"] < 30 or counts["red_left"] > 0:
        fail.append(f"{path}: the slow sphere on the left is not blue")
    if counts["red_right"] < 30 or counts["blue_right"] > 0:
        fail.append(f"{path}: the fast sphere on the right is not red")
if fail:
    sys.exit("FAIL: " + "; ".join(fail))
PY
echo "render_png: ok"
