#!/usr/bin/env bash
# [[stage.set_velocity]], [[stage.prescribe]] and the bond action's gap through run-stage
# (tests/data/velocities.toml): the bond action bonds the pair and the two floor contacts at exactly
# zero overlap (3 contacts); the prescribed sphere ends at x0 + v n dt (to the round-off of n
# additions, n 2^-53 |x|) and is free
# again; the mid-stage periodic checkpoint marks it prescribed (2 in /particles/fixed), and a run
# resumed from it on two threads gives the bits of an uninterrupted run on one (neither velocity is
# applied again); a group that selects no particle is refused, naming the entry, exit 3.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
scene=$src/data/velocities.toml
# With a periodic checkpoint from the middle of the stage, resumed below after the run that wrote it ended.
full_and_cut "$scene" pull 4000
cat "$tmp/full.log"
grep -q "stage pull: bonded 3 contacts" "$tmp/full.log" || { echo "FAIL: the touching pair and floor contacts were not bonded"; exit 1; }
grep -q "set the velocity of 1 particles (material \"B2\")" "$tmp/full.log" || { echo "FAIL: set_velocity report"; exit 1; }
grep -q "prescribed the velocity of 1 particles (ids 1 to 1)" "$tmp/full.log" || { echo "FAIL: prescribe report"; exit 1; }
grep -q "force on the 1 prescribed particles at the end" "$tmp/full.log" || { echo "FAIL: no force on the prescribed group"; exit 1; }

cp "$tmp/mid.h5" "$tmp/cut.restart.h5"
rm "$tmp/cut.h5"
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage pull --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 4000 --restart --quiet
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/cut.h5"

"$py" - "$tmp/start.h5" "$tmp/mid.h5" "$tmp/full.h5" <<'PY'
import sys, h5py
import numpy as np
s, m, f = (h5py.File(p, "r") for p in sys.argv[1:4])
def by_id(h, name):
    return dict(zip(h["particles/id"][:], h[name][:]))
mid_fixed = by_id(m, "particles/fixed")
assert mid_fixed[1] == 2 and mid_fixed[0] == 1 and mid_fixed[2] == 0, f"mid-stage flags {mid_fixed}"
def scalar(h, name):
    return np.ravel(h[name][()])[0]
assert scalar(m, "state/step") < scalar(f, "state/step"), "the periodic checkpoint is not mid-stage"
end_fixed = by_id(f, "particles/fixed")
assert end_fixed[1] == 0 and end_fixed[0] == 1, f"at the end: {end_fixed} (the prescribed sphere free, the held one held)"
n = int(scalar(f, "state/step") - scalar(s, "state/step"))
dt = float(scalar(f, "state/dt"))
x0, x1 = by_id(s, "particles/position")[1], by_id(f, "particles/position")[1]
v = np.array([0.002, 0.0, 0.0])
# n additions of v dt to x, each rounded to half an ulp of x: at most n 2^-53 |x| off.
err, bound = np.linalg.norm(x1 - (x0 + n * dt * v)), n * 2.0**-53 * np.linalg.norm(x1)
print(f"prescribed sphere moved {x1 - x0} m in {n} steps of {dt:.6g} s: {err:.2e} m from x0 + v n dt (round-off bound {bound:.2e} m)")
assert err <= bound, (err, bound)
assert np.array_equal(by_id(f, "particles/velocity")[1], v), "velocity not kept to the bit"
PY

if "$bin/run-stage" --scene "$scene" --stage nobody --in "$tmp/start.h5" --out "$tmp/n.h5" 2> "$tmp/nobody.log"; then
  echo "FAIL: an empty group was accepted"; exit 1
else
  rc=$?
fi
cat "$tmp/nobody.log"
[ "$rc" = 3 ] || { echo "FAIL: exit code $rc, expected 3"; exit 1; }
grep -q 'velocities.toml: stage.set_velocity\[0\] of stage "nobody" selects no particle (ids 100 to 200)' "$tmp/nobody.log" || { echo "FAIL: message"; exit 1; }
[ ! -e "$tmp/n.h5" ] || { echo "FAIL: output written"; exit 1; }
echo "stage velocities ok"
