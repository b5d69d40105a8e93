#!/usr/bin/env bash
# The segregation workflow (thesis §4.5) in small: the real scene with the automatic time step
# (frac 0.1: 2.8x the thesis's step) and 40 cycles instead of 94. Checks the physics the case is
# about, with margins the run exceeds several times (measured: see workflows/segregation/README.md):
#  - convection: the small spheres within one diameter of a side wall move down on average
#    (< -2 mm) and those more than three diameters from every wall move up (> +2 mm), as Knight,
#    Jaeger & Nagel (1993) observed; a bed that only bounced or compacted would move all columns
#    alike;
#  - the large sphere rises by more than half a small diameter (> 4 mm) from the floor;
#  - stage rise (5 g) from the same bed, 30 cycles: the large sphere rises by more than 12 mm
#    (measured +28 mm, against +7.4 mm at 3 g in 40 cycles).
# It also checks that sweep.toml is the same scene as scene.toml but for its time step and stages,
# and seeds.toml but for its lid and stages.
set -eu
bin=$1 src=$2 py=$3 root=$(dirname "$2")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
seg=$root/workflows/segregation
sed -e 's/^time_step = 1.1e-5 .*$/frac = 0.1/' -e 's/^duration = 4.70 .*$/duration = 2.0/' -e 's/^duration = 7.5 .*$/duration = 1.5/' \
  "$seg/scene.toml" > "$tmp/scene.toml"
grep -q '^frac = 0.1' "$tmp/scene.toml" && grep -q '^duration = 2.0' "$tmp/scene.toml" && grep -q '^duration = 1.5' "$tmp/scene.toml"
common() { sed -n '/^\[simulation\]/,/^\[\[stage\]\]/p' "$1" | grep -v '^time_step = \|^frac = '; }
if ! diff <(common "$seg/scene.toml") <(common "$seg/sweep.toml"); then echo "FAIL sweep.toml differs from scene.toml"; exit 1; fi
if ! diff <(sed -n '/^\[simulation\]/,/^\[\[stage\]\]/p' "$seg/scene.toml" | sed '$d') <(sed -n '/^\[simulation\]/,/^# The lid and the stage/p' "$seg/seeds.toml" | sed '$d'); then
  echo "FAIL seeds.toml differs from scene.toml"; exit 1
fi
"$bin/gen-primary" --scene "$tmp/scene.toml" --out "$tmp/settled.h5" --quiet
"$bin/run-stage" --scene "$tmp/scene.toml" --stage vibrate --in "$tmp/settled.h5" --out "$tmp/vibrated.h5" \
  --track "$tmp/intruder.csv" --track-ids 0 --track-every 50 --quiet
"$bin/run-stage" --scene "$tmp/scene.toml" --stage rise --in "$tmp/settled.h5" --out "$tmp/risen.h5" \
  --track "$tmp/rise.csv" --track-ids 0 --track-every 50 --quiet
"$py" "$root/scripts/segregation_report.py" --start "$tmp/settled.h5" --span "$tmp/vibrated.h5" --track "$tmp/intruder.csv" \
  --rise-track "$tmp/rise.csv" --intruder 0 --frequency 20 --summary "$tmp/summary.csv" --convection "$tmp/convection.csv" --png "$tmp/seg.png"
[ -s "$tmp/seg.png" ]
"$py" - "$tmp/summary.csv" <<'PY'
import csv, sys
v = {r["key"]: float(r["value"]) for r in csv.DictReader(open(sys.argv[1]))}
checks = [
    ("wall band moves down", v["wall_band_mean_dz_in_span"] < -0.002),
    ("core moves up", v["core_mean_dz_in_span"] > 0.002),
    ("large sphere rises", v["intruder_rise_in_span"] > 0.004),
    ("large sphere rises faster at 5 g", v["rise_intruder_centre_end"] - v["intruder_centre_start"] > 0.012),
]
for name, ok in checks:
    print(("ok   " if ok else "FAIL ") + name)
sys.exit(0 if all(ok for _, ok in checks) else 1)
PY
# seeds.toml's stage (a lid added to the settled bed, shaken with the box) for 5 cycles, and the
# report over several fills (one --start per run): the two runs counted, neither at the surface.
sed 's/^duration = 35.0 .*/duration = 0.25/' "$seg/seeds.toml" > "$tmp/seeds.toml"
grep -q '^duration = 0.25' "$tmp/seeds.toml"
"$bin/run-stage" --scene "$tmp/seeds.toml" --stage shake --in "$tmp/settled.h5" --out "$tmp/shaken.h5" \
  --track "$tmp/shake.csv" --track-ids 0 --track-every 100 --quiet
"$py" "$root/scripts/segregation_sweep.py" --start "$tmp/settled.h5" --start "$tmp/settled.h5" --run lid "$tmp/shake.csv" 20 3 \
  --run rise "$tmp/rise.csv" 20 5 --table "$tmp/seeds.csv" --summary "$tmp/spread.csv" --png "$tmp/seeds.png"
"$py" - "$tmp/spread.csv" <<'PY'
import csv, sys
v = {r["key"]: float(r["value"]) for r in csv.DictReader(open(sys.argv[1]))}
ok = v["runs"] == 2 and v["runs_reaching_surface"] == 0 and 4 <= v["cycles_per_run"] <= 5
print(("ok   " if ok else "FAIL ") + f"spread over two runs: {v}")
sys.exit(0 if ok else 1)
PY
