#!/usr/bin/env bash
# The helical-flow workflow (thesis §4.3) in small: tests/data/helical_flow_small.toml, 2,500
# spheres of the full case's sizes rained around an auger of half the full case's size, settled,
# then a still stage and a turning one (95 rpm). Checks, from scripts/helical_flow_report.py:
#  - at rest nothing is lifted: no net upward crossing of the counting plane (the bed only
#    settles; exact: a count; a sphere rocking on the plane as the bed settles may cross it up
#    and down again, so single up-crossings are allowed only as many as down-crossings);
#  - turning, the flight lifts: net upward crossings of the plane in the ramp's annulus (measured
#    119 particles in the 0.25 s; at least 20 asked, where at rest none cross);
#  - the flow rate stays below the ramp's volumetric capacity, π(r_out² − r_in²)·pitch·turns/s ×
#    the bed's bulk density: a flight cannot carry more than the bulk it sweeps, the rate of a plug
#    that rises with the flight without turning (measured efficiency 0.944 over these 0.25 s,
#    start-up included; 0.63 over 0.4 s from a bed settled 1.5 s; asked: between 0 and 1);
#  - the drive's work ∫ T ω dt is at least the particles' gain of potential plus kinetic energy
#    (the rest is dissipated; measured 128 J against 9.7 J): energy is not created;
#  - the power balance, from the spin stage's energy log (--energy-every 50): the walls' work
#    (the ledger's, exact for the steps, eq. P37) equals the report's ∫ T ω dt (trapezoids over the
#    wall log's rows every 50 steps) within TOL_WORK below, and it equals the potential and kinetic
#    energy gained plus what friction and damping dissipated plus the elastic energy stored since,
#    within 1 % of the energy scale at every row (the issue's bound, as the other energy tests)
#    and within 1 % of the work at the end; over half the work is dissipated.
set -eu
bin=$1 src=$2 py=$3 root=$(dirname "$2")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/helical_flow_small.toml
geometry="--walls shaft,cap,ramp --r-in 0.05 --r-out 0.15 --pitch 0.15 --plane 0.2"
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet > /dev/null
for stage in still spin; do
  energy=""
  [ $stage = spin ] && energy="--energy-every 50"
  "$bin/run-stage" --scene "$scene" --stage $stage --in "$tmp/settled.h5" --out "$tmp/$stage.h5" \
    --vtk "$tmp/vtk" --wall-forces "$tmp/walls_$stage.csv" --wall-forces-every 50 $energy --quiet
done
report() {
  "$py" "$root/scripts/helical_flow_report.py" --start "$tmp/settled.h5" --end "$tmp/$1.h5" --frames "$tmp/vtk/$1_particles.pvd" \
    --wall-forces "$tmp/walls_$1.csv" $geometry --rpm "$2" --flux "$tmp/flow_$1.csv" --power "$tmp/power_$1.csv" \
    --summary "$tmp/summary_$1.csv" $3 > /dev/null
}
report still 0 ""
report spin -95 "--png $tmp/helical.png"
[ -s "$tmp/helical.png" ]
# The case's renders (workflows/helical-flow/case.mk), at the end of the turn: in perspective and
# cut through the axis.
xvfb-run -a "$bin/dem-render" --quiet --relative-time --range 0,1 --box -0.25,-0.25,0.0,0.25,0.25,0.5 --size 320,240 \
  --in "$tmp/vtk/spin_particles.pvd" --time 0.25 --out "$tmp/perspective.png"
xvfb-run -a "$bin/dem-render" --quiet --relative-time --range 0,1 --box -0.25,-0.25,0.0,0.25,0.25,0.5 --size 320,240 \
  --in "$tmp/vtk/spin_particles.pvd" --time 0.25 --view cut --point 0,0,0.25 --normal 0,1,0 --out "$tmp/cut.png"
[ -s "$tmp/perspective.png" ] && [ -s "$tmp/cut.png" ] || { echo "FAIL: no renders"; exit 1; }
"$py" - "$tmp" <<'PY'
import csv, sys
def summary(name):
    return {r["key"]: float(r["value"]) for r in csv.DictReader(open(f"{sys.argv[1]}/summary_{name}.csv"))}
def ups(name):
    return sum(int(r["count_up"]) for r in csv.DictReader(open(f"{sys.argv[1]}/flow_{name}.csv")))
def downs(name):
    return sum(int(r["count_down"]) for r in csv.DictReader(open(f"{sys.argv[1]}/flow_{name}.csv")))
still, spin = summary("still"), summary("spin")
gain = spin["potential_energy_gain"] + spin["kinetic_energy_gain"]
checks = [
    ("at rest: %d particles cross upward, %d downward (no more up than down)" % (ups("still"), downs("still")), ups("still") <= downs("still")),
    ("at rest: the drive does no work (%.3g J)" % still["work"], still["work"] == 0),
    ("turning: %d particles net upward (>= 20)" % spin["net_count_up"], spin["net_count_up"] >= 20),
    ("volumetric efficiency %.3f (0 to 1)" % spin["volumetric_efficiency"], 0 < spin["volumetric_efficiency"] < 1),
    ("work %.4g J >= potential + kinetic gain %.4g J" % (spin["work"], gain), spin["work"] >= gain > 0),
]
energy = list(csv.DictReader(open(f"{sys.argv[1]}/spin.energy.csv")))
worst = max(abs(float(r["balance_error_relative"])) for r in energy)
last, first = energy[-1], energy[0]
ledger_work = float(last["work_walls_J"])
held = sum(float(last[k]) - float(first[k]) for k in
           ("kinetic_translation_J", "kinetic_rotation_J", "potential_J", "elastic_normal_J", "elastic_tangential_J"))
lost = sum(float(last[k]) for k in ("damping_normal_J", "friction_J", "global_damping_J", "rolling_J"))
# The report's work less the ledger's: the trapezoids over rows every 50 steps against the exact
# sum over the steps (measured 1.8 %: 128.4 J against 130.7 J); 5 % still fails a drive work off
# by a sign, a factor or a wall left out.
TOL_WORK = 0.05
error_end = float(last["balance_error_J"])
checks += [
    ("energy log: worst |error|/scale %.3g (< 0.01)" % worst, worst < 0.01),
    ("drive work: ledger %.4g J, report %.4g J (within %g)" % (ledger_work, spin["work"], TOL_WORK),
     abs(ledger_work / spin["work"] - 1) < TOL_WORK),
    ("power balance: work %.4g J = gained since the first row %.4g J + dissipated %.4g J; balance error at the end %.3g J"
     " (< 1 %% of the work)" % (ledger_work, held, lost, error_end), lost > 0.5 * ledger_work and abs(error_end) < 0.01 * ledger_work),
]
for name, ok in checks:
    print(("ok   " if ok else "FAIL ") + name)
sys.exit(0 if all(ok for _, ok in checks) else 1)
PY
