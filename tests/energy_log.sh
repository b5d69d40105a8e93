#!/usr/bin/env bash
# The energy log of run-stage (OUT with .energy.csv, docs/physics.md eq. P29-P39):
# 1. 40 spheres poured into a box (tests/data/energy_pour.toml): a row every energy_every =
#    0.005 s and at the last step; the balance error within 1 % of its scale at every row (the
#    scheme's own error is O((ω Δt)²) at each touch, ~1e-3 here), and the pour dissipates.
# 2. the same stage on two threads, resumed with --restart from a periodic checkpoint taken in
#    the middle, between two rows (step 1,500; a row every 1,328 steps), from a partial CSV
#    holding rows past that checkpoint: the finished CSV equals the uninterrupted run's on one
#    thread byte for byte (the ledger's sums are in the checkpoint).
# 3. a stage without energy_every writes no energy log; --energy-every N asks for one.
# 4. bad values: energy_every = 0 or -1 in the scene and --energy-every 0 are refused with the key.
# 5. 20 more spheres poured in during the stage ([[stage.insert]], eq. P45): the balance closes
#    within 1 % at every row as in 1 (without the energy they bring in it is off by their fall,
#    tens of % of the scale), and the energy brought in is their ½ m v² + m g z at insertion,
#    between the bounds computed here from their radius, speed and the region's heights.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/catch_checkpoint.sh"
pour=$src/data/energy_pour.toml

"$bin/gen-primary" --scene "$pour" --out "$tmp/start.h5" --quiet
OMP_NUM_THREADS=1 "$bin/run-stage" --scene "$pour" --stage pour --in "$tmp/start.h5" --out "$tmp/full.h5" --quiet
"$py" - "$tmp/full.energy.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) >= 40, len(rows)
worst = max(abs(float(r["balance_error_relative"])) for r in rows)
assert worst < 0.01, f"balance error {worst:.3g} of the scale"
last = rows[-1]
lost = sum(float(last[k]) for k in ("damping_normal_J", "friction_J", "global_damping_J"))
drop = float(rows[0]["potential_J"]) - float(last["potential_J"])
assert lost > 0.5 * drop > 0, f"dissipated {lost} J of a fall of {drop} J"
print(f"pour: {len(rows)} rows, worst |error|/scale {worst:.2g}, dissipated {lost:.3g} J of {drop:.3g} J of fall")
PY

# 2. Resumed on two threads from a periodic checkpoint in the middle of the stage.
catch_checkpoint "$tmp/cut.restart.h5" "$tmp/mid.h5" -- env OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$pour" --stage pour --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 1500 --quiet
cmp "$tmp/full.energy.csv" "$tmp/cut.energy.csv" || { echo "FAIL: two threads give another energy log than one"; exit 1; }
mv "$tmp/mid.h5" "$tmp/cut.restart.h5"
cp "$tmp/full.energy.csv" "$tmp/cut.energy.csv.partial"
rm "$tmp/cut.h5" "$tmp/cut.energy.csv"
OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$pour" --stage pour --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every 1500 --restart 2> "$tmp/cut.log"
grep "resuming" "$tmp/cut.log"
cmp "$tmp/full.energy.csv" "$tmp/cut.energy.csv" || { echo "FAIL: the resumed energy log differs from the uninterrupted one"; exit 1; }
[ ! -e "$tmp/cut.energy.csv.partial" ] || { echo "FAIL: partial file left"; exit 1; }

# 3. No energy_every: no log; --energy-every asks for one.
sed '/^energy_every/d' "$pour" > "$tmp/quiet.toml"
"$bin/run-stage" --scene "$tmp/quiet.toml" --stage pour --in "$tmp/start.h5" --out "$tmp/none.h5" --quiet
[ ! -e "$tmp/none.energy.csv" ] || { echo "FAIL: an energy log nobody asked for"; exit 1; }
"$bin/run-stage" --scene "$tmp/quiet.toml" --stage pour --in "$tmp/start.h5" --out "$tmp/cli.h5" --energy-every 1000 --quiet
"$py" - "$tmp/cli.energy.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
steps = [int(r["step"]) for r in rows]
assert steps[1] - steps[0] == 1000, steps[:3]
PY

# 4. Bad values.
for bad in 0.0 -1.0; do
  sed "s/^energy_every = .*/energy_every = $bad/" "$pour" > "$tmp/bad.toml"
  if "$bin/run-stage" --scene "$tmp/bad.toml" --stage pour --in "$tmp/start.h5" --out "$tmp/bad.h5" 2> "$tmp/bad.log"; then
    echo "FAIL: energy_every = $bad accepted"; exit 1
  fi
  grep -q "energy_every" "$tmp/bad.log" && grep -q "bad.toml" "$tmp/bad.log" || { echo "FAIL: unclear message:"; cat "$tmp/bad.log"; exit 1; }
done
if "$bin/run-stage" --scene "$pour" --stage pour --in "$tmp/start.h5" --out "$tmp/bad.h5" --energy-every 0 2> "$tmp/bad.log"; then
  echo "FAIL: --energy-every 0 accepted"; exit 1
fi
grep -q -- "--energy-every" "$tmp/bad.log" || { echo "FAIL: unclear message:"; cat "$tmp/bad.log"; exit 1; }
# 5. Insertion during the stage.
cat "$pour" - > "$tmp/insert.toml" <<'TOML'

[[stage.insert]]
region = { type = "box", min = [0.0, 0.0, 0.075], max = [0.02, 0.02, 0.095] }
material = "glass"
radius_min = 0.0015
radius_max = 0.0015
count_rate = 400.0
total_count = 20
velocity = [0.0, 0.0, -0.3]
seed = 9
attempts = 1000
TOML
"$bin/run-stage" --scene "$tmp/insert.toml" --stage pour --in "$tmp/start.h5" --out "$tmp/insert.h5" --quiet
"$py" - "$tmp/insert.energy.csv" "$tmp/insert.h5" <<'PY'
import csv, math, sys
import h5py
rows = list(csv.DictReader(open(sys.argv[1])))
with h5py.File(sys.argv[2], "r") as f:
    n = len(f["/particles/radius"][:])
assert n == 60, f"{n} particles at the end, 60 expected"
worst = max(abs(float(r["balance_error_relative"])) for r in rows)
inserted = float(rows[-1]["inserted_J"])
m = 2500.0 * 4.0 / 3.0 * math.pi * 0.0015 ** 3
# Centres between 0.075 + r and 0.095 - r; ½ m v² at 0.3 m/s (the half-step shift, v Δt/2, is 1e-7 m).
lo, hi = 20 * m * (0.045 + 9.81 * (0.075 + 0.0015)), 20 * m * (0.045 + 9.81 * (0.095 - 0.0015))
print(f"insert: worst |error|/scale {worst:.2g}; brought in {inserted:.4g} J (bounds {lo:.4g} to {hi:.4g} J)")
assert worst < 0.01, f"balance error {worst:.3g} of the scale with insertion"
assert lo <= inserted <= hi, "energy brought in outside its bounds"
PY
echo "energy log: OK"
