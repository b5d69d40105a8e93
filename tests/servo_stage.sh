#!/usr/bin/env bash
# [[stage.servo]]: the lid of a box of 150 settled spheres reaches a target stress of 1 kPa within
# 2 % and holds it, then holds it on average while a side wall squeezes the sample; the per-wall
# CSV of run-stage --wall-forces is what is checked (lid force / the lid's area between the side
# walls, which shrinks as the side wall moves in: walls/container.hpp).
set -eu
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/servo.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null
"$bin/run-stage" --scene "$scene" --stage press --in "$tmp/settled.h5" --out "$tmp/pressed.h5" --wall-forces "$tmp/press.csv" \
  --wall-forces-every 20 --quiet
"$bin/run-stage" --scene "$scene" --stage squeeze --in "$tmp/pressed.h5" --out "$tmp/squeezed.h5" --wall-forces "$tmp/squeeze.csv" \
  --wall-forces-every 20 --quiet
[ ! -e "$tmp/press.csv.partial" ] || { echo "partial CSV left behind"; exit 1; }
"$py" - "$tmp/press.csv" "$tmp/squeeze.csv" "$tmp/pressed.h5" <<'PY'
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
squeeze = lid(sys.argv[2], 0.001)
half = squeeze[len(squeeze) // 2:]
mean = sum(half) / len(half)
print(f"squeeze: second half mean {mean:.1f} Pa ({100 * (mean / target - 1):+.2f} %), single rows {min(half):.0f} .. {max(half):.0f} Pa")
assert abs(mean / target - 1) <= 0.02, "while the interior changes the mean stress must stay within 2 %"
PY
