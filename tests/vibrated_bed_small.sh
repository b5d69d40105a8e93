#!/usr/bin/env bash
# The vibrated-bed workflow (thesis §4.6) in small: tests/data/vibrated_bed_small.toml, the full
# case's bed cut to 10 mm wide (189 spheres, same depth, materials, step and shaking: 25 Hz, 6 g),
# 10 cycles, the first 4 left out. Checks, from the floor's force (run-stage --wall-forces):
#  - period doubling: at Γ = 6 the bed flies for about two cycles (the inelastic bouncing ball
#    flies 1.94), so it hits the floor every other cycle and the floor force has a Fourier
#    component at f/2 of at least 0.4 of its mean (measured 0.73; a train of short impacts every
#    other cycle gives 1; the same bed at Γ = 3, which lands every cycle, gives 0.01);
#  - the floor carries the bed's weight on average: mean force M·g within 10 % (measured +1.3 %;
#    the bed's momentum at the two ends of the span, the same phase of its two-cycle motion,
#    differs by a few % of M·g·T per cycle at most);
#  - the bed leaves the floor after the box's acceleration passes −g (sin ωt = 1/Γ: 0.027 cycles,
#    less 0.01 for the sampling) and by 0.15 cycles (measured 0.09: the bed, dilated by the
#    impact, takes a while longer to leave than a rigid block would).
set -eu
bin=$1 src=$2 py=$3 root=$(dirname "$2")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/vibrated_bed_small.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null
"$bin/run-stage" --scene "$scene" --stage vibrate --in "$tmp/settled.h5" --out "$tmp/end.h5" \
  --vtk "$tmp/vtk" --wall-forces "$tmp/walls.csv" --wall-forces-every 50 --quiet
"$py" "$root/scripts/vibrated_bed_report.py" --end "$tmp/end.h5" --wall-forces "$tmp/walls.csv" \
  --frames "$tmp/vtk/vibrate_particles.pvd" --frequency 25 --acceleration 58.86 --skip 4 \
  --summary "$tmp/summary.csv" --png "$tmp/bed.png" > /dev/null
[ -s "$tmp/bed.png" ]
"$py" - "$tmp/summary.csv" <<'PY'
import csv, sys
v = {r["key"]: float(r["value"]) for r in csv.DictReader(open(sys.argv[1]))}
checks = [
    ("floor force at f/2 %.3f of its mean (>= 0.4)" % v["floor_force_component_half_f"],
     v["floor_force_component_half_f"] >= 0.4),
    ("mean floor force %.4f M g (1 +- 0.1)" % v["floor_force_mean"], abs(v["floor_force_mean"] - 1) <= 0.1),
    ("bed leaves the floor at phase %.3f (%.3f - 0.01 to 0.15)" % (v["bed_leaves_floor_phase"], v["ball_leaves_plate_phase"]),
     v["ball_leaves_plate_phase"] - 0.01 <= v["bed_leaves_floor_phase"] <= 0.15),
]
for name, ok in checks:
    print(("ok   " if ok else "FAIL ") + name)
sys.exit(0 if all(ok for _, ok in checks) else 1)
PY
