#!/usr/bin/env bash
# [[stage.servo]]: the lid of a box of 150 settled spheres reaches a target stress of 1 kPa within
# 2 % and holds it; then a side wall squeezes the sample at 1 mm/s, once under proportional control
# (which lags: an error ~ rate / gain) and once under PI control (integral_time), which must hold
# the target on average; the per-wall CSV of run-stage --wall-forces is what is checked (lid force /
# the lid's area between the side walls, which shrinks as the side wall moves in:
# walls/container.hpp).
set -eu
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/servo.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null
"$bin/run-stage" --scene "$scene" --stage press --in "$tmp/settled.h5" --out "$tmp/pressed.h5" --wall-forces "$tmp/press.csv" \
  --wall-forces-every 20 --quiet
"$bin/run-stage" --scene "$scene" --stage squeeze --in "$tmp/pressed.h5" --out "$tmp/squeezed.h5" --wall-forces "$tmp/squeeze.csv" \
  --wall-forces-every 20 --quiet
"$bin/run-stage" --scene "$scene" --stage squeeze_pi --in "$tmp/pressed.h5" --out "$tmp/squeezed_pi.h5" --wall-forces "$tmp/squeeze_pi.csv" \
  --wall-forces-every 20 --quiet
[ ! -e "$tmp/press.csv.partial" ] || { echo "partial CSV left behind"; exit 1; }
"$py" - "$tmp/press.csv" "$tmp/squeeze.csv" "$tmp/pressed.h5" "$tmp/squeeze_pi.csv" <<'PY'
import csv, sys
import h5py
target = 1000.0
t0 = float(h5py.File(sys.argv[3], "r")["/state/time"][0])  # the squeeze starts here
def lid(path, squeeze_speed=0.0):
    rows = [r for r in csv.DictReader(open(path)) if r["wall"] == "box.zmax"]
    walls = {r["wall"] for r in csv.DictReader(open(path))}
    assert walls == {"box.xmin", "box.xmax", "box.ymin", "box.ymax", "box.zmin", "box.zmax"}, walls
    # box.xmax moves in at squeeze_speed from t0: the lid presses on 0.02 m x (0.02 m - travel).
    return [float(r["fz_N"]) / (0.02 * (0.02 - squeeze_speed * max(0.0, float(r["time_s"]) - t0))) for r in rows]
press = lid(sys.argv[1])
tail = press[int(0.75 * len(press)):]  # after the approach (about 15 % of the stage) and the build-up
worst = max(abs(s / target - 1) for s in tail)
print(f"press: {len(press)} rows; last 25 %: stress {min(tail):.1f} .. {max(tail):.1f} Pa, worst deviation {100 * worst:.2f} %")
assert worst <= 0.02, "the servo must hold the target within 2 %"
def second_half(path, label):
    rows = lid(path, 0.001)
    half = rows[len(rows) // 2:]
    mean = sum(half) / len(half)
    within = sum(abs(s / target - 1) <= 0.10 for s in half) / len(half)
    print(f"{label}: second half mean {mean:.1f} Pa ({100 * (mean / target - 1):+.2f} %), single rows {min(half):.0f} .. {max(half):.0f} Pa, "
          f"{100 * within:.1f} % of them within 10 %")
    return mean / target - 1, within
err_p, _ = second_half(sys.argv[2], "squeeze, proportional (gain 0.2)")
err_pi, within_pi = second_half(sys.argv[4], "squeeze, PI (gain 0.2, integral_time 0.003 s)")
# The squeezed 150-sphere sample is chaotic: its force chains buckle now and then, and the lid,
# held by 8-15 contacts, loses part of its support until the servo has moved it on; which
# trajectory, and so when and how deep these drops are, changes with the last bit of anything.
# The bounds come from 35 runs with the time step changed by up to 0.4 % (frac 0.0996 .. 0.1004)
# and three summation orders (before and after the load blocks, and with the walls summed in the
# force loop): the PI mean was within 1.94 % of the target in every run (2.5 % asked), within
# 0.4 % in 31 of them; 69.5 .. 100 % of its rows (20 steps each) were within 10 % (60 % asked).
# The proportional mean ranged -8.6 .. +6.9 %; whether it lags more than the PI one is true of most
# runs, not of all (2 of 35 not), so it is shown here and tested on a plant without chaos, against
# the analytic lag, in tests/test_servo.cpp.
assert abs(err_pi) <= 0.025, "while the interior changes the PI servo must hold the mean stress within 2.5 %"
assert within_pi >= 0.60, "the PI servo must hold most rows within 10 %"
PY
