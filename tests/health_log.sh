#!/usr/bin/env bash
# The health log of run-stage (OUT with .health.csv), against answers known by hand:
# 1. free fall (tests/data/health_fall.toml): 20 spheres at rest, apart, fall without touching
#    anything, so every row has KE = ½ M g² t² (t since the stage began; relative 1e-9, the
#    leapfrog's velocity is exact for a constant force), no rotation, no contact, coordination 0;
#    one row every health_every = 0.004 s (round(0.004/dt) steps) and one at the last step.
# 2. the same stage on two threads, resumed with --restart from a periodic checkpoint taken in
#    the middle, from a partial CSV that holds rows past that checkpoint (as a killed run leaves):
#    the finished CSV equals the uninterrupted run's on one thread byte for byte, no row twice.
# 3. --health-every overrides the scene (in steps).
# 4. a column of 8 equal spheres in a tube (tests/data/health_column.toml): 7 pair contacts,
#    coordination 1.75, 7 bonds intact and none broken after the stage's `bond`.
# 5. bad values: health_every = -1 in the scene and --health-every 0 are refused with the key.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
fall=$src/data/health_fall.toml

"$bin/gen-primary" --scene "$fall" --out "$tmp/start.h5" --quiet
OMP_NUM_THREADS=1 "$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/full.h5" 2> "$tmp/full.log"
cat "$tmp/full.log"
grep -q "time step" "$tmp/full.log" || { echo "FAIL: no time step printed at the start"; exit 1; }
grep -q "particle-steps/s" "$tmp/full.log" || { echo "FAIL: no end summary"; exit 1; }
[ "$(grep -c '^health: ' "$tmp/full.log")" -ge 10 ] || { echo "FAIL: no console line per row"; exit 1; }
OMP_NUM_THREADS=1 "$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/quiet.h5" --quiet 2> "$tmp/quiet.log"
[ ! -s "$tmp/quiet.log" ] || { echo "FAIL: --quiet printed:"; cat "$tmp/quiet.log"; exit 1; }
cmp "$tmp/full.health.csv" "$tmp/quiet.health.csv"

"$py" - "$tmp/full.health.csv" "$tmp/start.h5" <<'PY'
import csv, math, sys
import h5py
rows = list(csv.DictReader(open(sys.argv[1])))
s = h5py.File(sys.argv[2], "r")
M, t0, step0 = s["particles/mass"][:].sum(), s["state/time"][0], s["state/step"][0]
assert abs(s["particles/velocity"][:]).max() == 0, "the start is not at rest"
dt = float(rows[0]["dt_s"])
steps = math.ceil(0.05 / dt - 1e-9)
every = round(0.004 / dt)
want = [step0 + k * every for k in range(1, steps // every + 1)]
if steps % every: want.append(step0 + steps)
got = [int(r["step"]) for r in rows]
assert got == want, f"rows at steps {got[:5]}..., expected {want[:5]}... ({len(got)} rows, expected {len(want)})"
g = 9.81
worst = 0
for r in rows:
    t = float(r["time_s"]) - t0
    ke = 0.5 * M * g * g * t * t
    worst = max(worst, abs(float(r["kinetic_translation_J"]) / ke - 1))
    assert float(r["kinetic_rotation_J"]) == 0, r
    assert int(r["pair_contacts"]) == 0 and int(r["wall_contacts"]) == 0 and float(r["coordination"]) == 0, r
    walls = [k for k in r if k.startswith("force_box.")]
    assert len(walls) == 6 and all(float(r[k]) == 0 for k in walls) and float(r["elastic_bound_J"]) == 0, r
    assert int(r["particles"]) == 20 and float(r["dt_s"]) == dt, r
assert worst < 1e-9, f"kinetic energy off ½ M g² t² by {worst:.3g} (relative)"
print(f"free fall: {len(rows)} rows every {every} steps, KE = ½ M g² t² within {worst:.2g} (relative)")
PY

# 2. Resumed on two threads from a periodic checkpoint in the middle of the stage.
catch_checkpoint "$tmp/cut.restart.h5" "$tmp/mid.h5" -- env OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 1000 --quiet
cmp "$tmp/full.health.csv" "$tmp/cut.health.csv" || { echo "FAIL: two threads give another health log than one"; exit 1; }
# As a run killed after that checkpoint leaves it: the periodic checkpoint, and a partial CSV with
# rows written after it (here all of them); the finished file of the killed run is not there.
mv "$tmp/mid.h5" "$tmp/cut.restart.h5"
cp "$tmp/full.health.csv" "$tmp/cut.health.csv.partial"
rm "$tmp/cut.h5" "$tmp/cut.health.csv"
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 1000 --restart 2> "$tmp/cut.log"
grep "resuming" "$tmp/cut.log"
"$py" - "$tmp/cut.health.csv" <<'PY'
import csv, sys
steps = [int(r["step"]) for r in csv.DictReader(open(sys.argv[1]))]
assert len(steps) == len(set(steps)) and steps == sorted(steps), "duplicate or unordered rows"
PY
cmp "$tmp/full.health.csv" "$tmp/cut.health.csv" || { echo "FAIL: the resumed health log differs from the uninterrupted one"; exit 1; }
[ ! -e "$tmp/cut.health.csv.partial" ] || { echo "FAIL: partial file left"; exit 1; }

# 3. --health-every in steps overrides the scene.
"$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/every.h5" --health-every 500 --quiet
"$py" - "$tmp/every.health.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
steps = math.ceil(0.05 / float(rows[0]["dt_s"]) - 1e-9)
assert len(rows) == steps // 500 + (steps % 500 != 0), len(rows)
assert int(rows[0]["step"]) == 500 and int(rows[1]["step"]) == 1000, rows[:2]
PY

# 4. A column of 8 spheres: coordination 2 x 7 / 8.
column=$src/data/health_column.toml
"$bin/gen-primary" --scene "$column" --out "$tmp/column.h5" --quiet
"$bin/run-stage" --scene "$column" --stage bonded --in "$tmp/column.h5" --out "$tmp/bonded.h5" --quiet
"$py" - "$tmp/bonded.health.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) >= 2, len(rows)
for r in rows:
    assert int(r["particles"]) == 8 and int(r["pair_contacts"]) == 7, r
    assert float(r["coordination"]) == 1.75, r
    assert int(r["bonds"]) == 7 and int(r["bonds_broken"]) == 0, r
    assert int(r["wall_contacts"]) >= 1 and 0 < float(r["max_overlap_per_radius"]) < 0.01, r
    assert float(r["force_tube.zmin_N"]) > 0 and float(r["elastic_bound_J"]) > 0, r
print(f"column: {len(rows)} rows, 7 contacts, coordination 1.75, 7 bonds intact")
PY

# 5. Bad values.
sed 's/^health_every = 0.004/health_every = -1.0/' "$fall" > "$tmp/bad.toml"
if "$bin/run-stage" --scene "$tmp/bad.toml" --stage fall --in "$tmp/start.h5" --out "$tmp/bad.h5" 2> "$tmp/bad.log"; then
  echo "FAIL: health_every = -1 accepted"; exit 1
fi
cat "$tmp/bad.log"
grep -q "health_every" "$tmp/bad.log" && grep -q "bad.toml" "$tmp/bad.log" && grep -q -- "-1" "$tmp/bad.log" ||
  { echo "FAIL: the message does not name the file, the key and the value"; exit 1; }
if "$bin/run-stage" --scene "$fall" --stage fall --in "$tmp/start.h5" --out "$tmp/bad.h5" --health-every 0 2> "$tmp/bad2.log"; then
  echo "FAIL: --health-every 0 accepted"; exit 1
fi
cat "$tmp/bad2.log"
grep -q -- "--health-every" "$tmp/bad2.log" || { echo "FAIL: the message does not name --health-every"; exit 1; }
[ ! -e "$tmp/bad.h5" ] && [ ! -e "$tmp/bad.health.csv" ] || { echo "FAIL: a refused run left outputs"; exit 1; }
echo "health log ok"
