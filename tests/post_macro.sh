#!/usr/bin/env bash
# post-macro end to end: every output written and read back (check_post_output.py), --kinetic,
# the old displacement-only use, and bad command lines rejected (exit 2, or 3 for a grid too
# large for the sample) with a clear message and nothing written.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
scene=$src/data/small.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null || exit 1
"$bin/run-stage" --scene "$scene" --stage shake --in "$tmp/settled.h5" --out "$tmp/shaken.h5" --quiet > /dev/null 2>&1 || exit 1
out=$tmp/out
# The settled bed carries its weight (the shaken one is in the air at the end of its stage); the
# displacement is taken from the shaken state, which lacks the removed particles: NaN there.
# The first region (the profile's and the grid's) covers the box up to 12 mm; the second a corner.
lo=0,0,0 hi=0.02,0.02,0.012
"$bin/post-macro" --reference "$tmp/shaken.h5" --in "$tmp/settled.h5" --vtk "$out/particles.vtu" --chains "$out/chains.vtp" \
  --grid "$out/grid.vti" --cell 0.002 --width 0.002 --average-csv "$out/averages.csv" --stress-csv "$out/stress_profile.csv" \
  --csv "$out/profile.csv" --region "box:$lo,$hi" --region box:0,0,0,0.01,0.01,0.006 --bins 4 --threads 2 > "$tmp/log" \
  || { cat "$tmp/log"; exit 1; }
grep -q "matched by id" "$tmp/log" && grep -q "wall contacts; contact stress (no kinetic part)" "$tmp/log" || { cat "$tmp/log"; fail=1; }
"$py" "$src/check_post_output.py" "$out" "$tmp/settled.h5" "$tmp/shaken.h5" 0.002 "$lo" "$hi" || fail=1
[ "$(grep -vc '^#' "$out/profile.csv")" -eq 5 ] || { echo "displacement profile: 4 rows expected"; fail=1; }

# --kinetic: the tensors gain the kinetic part, which is also written on its own.
"$bin/post-macro" --in "$tmp/settled.h5" --vtk "$tmp/k.vtu" --average-csv "$tmp/k.csv" --kinetic > "$tmp/log" || { cat "$tmp/log"; exit 1; }
"$py" - "$out/particles.vtu" "$tmp/k.vtu" <<'PY' || fail=1
import sys
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
def read(p):
    r = vtkXMLUnstructuredGridReader(); r.SetFileName(p); r.Update(); return r.GetOutput().GetPointData()
a, b = read(sys.argv[1]), read(sys.argv[2])
contact, total, kin = (vtk_to_numpy(d.GetArray(n)) for d, n in ((a, "stress"), (b, "stress"), (b, "kinetic_stress")))
assert np.allclose(total, contact + kin, rtol=1e-12, atol=1e-12 * np.abs(total).max()), "stress = contact + kinetic"
assert np.all(kin[:, [0, 4, 8]] <= 0) and np.any(kin[:, 0] < 0), "kinetic stress: compressive (negative) diagonal"
assert a.GetArray("displacement") is not None and b.GetArray("displacement") is None, "displacement only with --reference"
print("kinetic ok")
PY
grep -q "contact + kinetic stress" "$tmp/k.csv" || { echo "k.csv does not say it holds the kinetic part"; fail=1; }

# --quiet, as the other tools: the same files, nothing on stdout.
"$bin/post-macro" --in "$tmp/settled.h5" --vtk "$tmp/q.vtu" --average-csv "$tmp/q.csv" --kinetic --quiet > "$tmp/log" 2> "$tmp/err" \
  || { cat "$tmp/log" "$tmp/err"; exit 1; }
if [ ! -s "$tmp/log" ] && [ ! -s "$tmp/err" ] && cmp -s "$tmp/q.csv" "$tmp/k.csv"; then echo "ok   --quiet: the same table, nothing printed"
else echo "FAIL --quiet printed:"; cat "$tmp/log" "$tmp/err"; fail=1; fi

# Bad command lines: exit 2 (3 for the grid too large), the message, nothing written.
check() {  # check NAME CODE PATTERN -- args...
  local name=$1 want=$2 pattern=$3; shift 4
  rm -rf "$tmp/bad"; mkdir "$tmp/bad"
  "$bin/post-macro" "$@" > "$tmp/msg" 2>&1; local got=$?
  if [ "$got" != "$want" ] || ! grep -q -- "$pattern" "$tmp/msg"; then
    echo "FAIL $name: exit $got (want $want), pattern '$pattern' in:"; sed 's/^/    /' "$tmp/msg"; fail=1
  elif [ -n "$(ls -A "$tmp/bad")" ]; then
    echo "FAIL $name: wrote $(ls -A "$tmp/bad")"; fail=1
  else echo "ok   $name"; fi
}
in=(--in "$tmp/shaken.h5")
b=$tmp/bad
check "grid without cell" 2 "--grid requires --cell" -- "${in[@]}" --grid "$b/g.vti" --width 0.002
check "grid without width" 2 "--grid requires --width" -- "${in[@]}" --grid "$b/g.vti" --cell 0.002
check "cell without grid" 2 "--cell requires --grid" -- "${in[@]}" --cell 0.002 --vtk "$b/p.vtu"
check "negative width" 2 "--width: must be a positive length in metres, got -0.002" -- "${in[@]}" --grid "$b/g.vti" --cell 0.002 --width -0.002
check "csv without reference" 2 "--csv requires --reference" -- "${in[@]}" --csv "$b/d.csv" --vtk "$b/p.vtu"
check "region with 3 numbers" 2 'expected 6 numbers x0,y0,z0,x1,y1,z1, got 3' -- "${in[@]}" --region box:0,0,0 --stress-csv "$b/s.csv"
check "region upside down" 2 'the upper corner must exceed the lower one along z' -- "${in[@]}" --region box:0,0,1,1,1,0 --stress-csv "$b/s.csv"
check "region not a box" 2 'expected box:x0,y0,z0,x1,y1,z1' -- "${in[@]}" --region sphere:0,0,0,1 --stress-csv "$b/s.csv"
check "region not a number" 2 '"1e" is not a finite number' -- "${in[@]}" --region box:0,0,0,1,1,1e --stress-csv "$b/s.csv"
check "output named twice" 2 "is named twice, or is an input" -- "${in[@]}" --vtk "$b/x.vtu" --chains "$b/x.vtu"
check "output over the input" 2 "is named twice, or is an input" -- "${in[@]}" --reference "$tmp/settled.h5" --vtk "$tmp/settled.h5"
check "bins 0" 2 "--bins: Value 0 not in range" -- "${in[@]}" --stress-csv "$b/s.csv" --bins 0
check "grid too large" 3 "nodes over .* is more than the limit of 1e8" -- "${in[@]}" --grid "$b/g.vti" --cell 1e-6 --width 1e-6 --vtk "$b/p.vtu"
check "missing checkpoint" 2 "File does not exist" -- --in "$tmp/none.h5" --vtk "$b/p.vtu"
check "missing reference checkpoint" 2 "File does not exist" -- --in "$tmp/shaken.h5" --reference "$tmp/none.h5" --vtk "$b/p.vtu"
ls "$tmp"/*.tmp "$out"/*.tmp 2>/dev/null && { echo "temporary files left behind"; fail=1; }
[ $fail -eq 0 ] && echo "post-macro ok"
exit $fail
