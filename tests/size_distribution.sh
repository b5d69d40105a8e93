#!/usr/bin/env bash
# [generation.size] through gen-primary: a sieve curve (tests/data/sieve.toml) gives the report of
# asked against realised mass fraction passing each sieve (stdout and --sizes CSV); the checkpoint holds those radii, within
# the curve's diameters and without overlap; the same seed gives the same bits; a bad curve stops
# with exit 3 and names the row.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/sieve.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/a.h5" --sizes "$tmp/sizes.csv" --threads 1 --quiet > "$tmp/a.log"
"$bin/gen-primary" --scene "$scene" --out "$tmp/b.h5" --threads 1 --quiet > /dev/null
cat "$tmp/a.log"
grep -q "gen-primary: size distribution sieve, 400 random spheres: asked, realised" "$tmp/a.log"
[ "$(grep -c "mass fraction passing d = " "$tmp/a.log")" = 4 ] || { echo "FAIL: not one report line per sieve"; exit 1; }
"$py" - "$tmp/a.h5" "$tmp/b.h5" "$tmp/a.log" "$tmp/sizes.csv" <<'PY'
import csv, re, sys
import h5py
import numpy as np
fa, fb = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
a, x = fa["/particles/radius"][:], fa["/particles/position"][:]
assert np.array_equal(a, fb["/particles/radius"][:]) and np.array_equal(x, fb["/particles/position"][:]), "same seed, other spheres"
a, x = a[np.argsort(fa["/particles/id"][:])], x[np.argsort(fa["/particles/id"][:])]
assert np.all(np.diff(a) <= 0), "placed largest first (ids in placement order)"
gap = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2) - (a[:, None] + a[None, :])
np.fill_diagonal(gap, 0)
assert gap.min() >= 0, "spheres overlap"
assert len(a) == 400 and a.min() >= 0.5e-3 and a.max() <= 1.5e-3, "radii outside the sieve curve's diameters"
m = a ** 3
for line in open(sys.argv[3]):
    g = re.search(r"mass fraction passing d = ([0-9.e+-]+) m: ([0-9.e+-]+), ([0-9.e+-]+)", line)
    if not g: continue
    d, asked, realised = map(float, g.groups())
    mine = m[2 * a < d].sum() / m.sum()
    assert abs(mine - realised) < 1e-3, f"report says {realised} at d = {d}, the checkpoint {mine}"
    # 400 spheres: the standard error of a mass fraction is at most 0.036 here (at 2 mm, by the
    # delta method on 400,000 draws of this curve); 4 of them.
    assert abs(realised - asked) < 0.15, f"mass fraction passing {d} m: asked {asked}, realised {realised}"
with open(sys.argv[4]) as f:
    assert f.readline().startswith("# gen-primary: size distribution sieve, 400 random spheres")
    rows = list(csv.DictReader(f))
assert [float(r["diameter_m"]) for r in rows] == [1.0e-3, 1.5e-3, 2.0e-3, 3.0e-3], rows
assert [float(r["asked"]) for r in rows] == [0.0, 0.2, 0.5, 1.0], rows
for r in rows:
    d = float(r["diameter_m"])
    assert abs(float(r["realised"]) - m[2 * a < d].sum() / m.sum()) < 1e-9, r
print("ok   sieve report (stdout and --sizes CSV) matches the checkpoint and the curve")
PY
sed 's/\[2.0e-3, 0.5\], \[3.0e-3, 1.0\]/[2.0e-3, 0.5], [3.0e-3, 0.9]/' "$scene" > "$tmp/bad.toml"
set +e
"$bin/gen-primary" --scene "$tmp/bad.toml" --out "$tmp/bad.h5" > "$tmp/bad.log" 2>&1; rc=$?
set -e
if [ $rc != 3 ] || ! grep -q "generation.size.sieve\[3\] = \[...\]: the last row's fraction passing is 0.9" "$tmp/bad.log"; then
  echo "FAIL bad sieve curve: exit $rc"; cat "$tmp/bad.log"; exit 1
fi
[ -e "$tmp/bad.h5" ] && { echo "FAIL output written after a bad curve"; exit 1; }
echo "ok   bad sieve curve refused"
