#!/usr/bin/env bash
# The sand-production case small (workflows/sand-production/small.toml: the case's chain, material,
# confinement, fluid and drawdown on 1,700 spheres): settle, compact, load to 18 MPa by servo walls,
# cement, drill the well, then produce with the fluid and, as the control, without it.
# Checks (measured: 75 grains produced with the fluid, 5 without; the case's README.md):
# 1. Sand is produced with the fluid on (the sink log's total > 0) and at most a quarter as many
#    grains without it: the two runs differ only by [stage.fluid]; the few grains of the dry run are
#    the rim of the hole still creeping in after the 5 ms of phase 1 (whose own sink counted those
#    that fell in during drilling).
# 2. The stress turns around the hole: next to the wall (first bin) the hoop stress is more than
#    three times the radial one (Kirsch: sigma_rr -> 0, sigma_tt -> 2 sigma0), and sigma_tt >
#    sigma_rr in every bin within 2a.
# 3. The bonded rock yields at the wall: the broken-bond fraction within 2a is more than twice the
#    fraction beyond 2.5a. (Where it yields, the hoop stress no longer peaks at the wall but at the
#    yielded zone's edge: README.md.)
# 4. Kirsch (docs/physics.md eq. P80-P83) where the rock stays elastic: the same loaded slab cemented
#    with bonds that do not break (cohesion and tensile strength 1e5 N: far above the forces carried,
#    and near enough that the neighbour search's bond reach stays under a millimetre) and drilled; every bin at
#    r >= 2a within P83 of Kirsch with sigma0 = 18 MPa, and no bond broken. The thesis's rock misses
#    it (2 of those 3 bins): it yields beyond 2a at 18 MPa (README.md, "Measured"), reported by
#    scripts/well_report.py, not checked.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd) py=$3
case_dir=$src/../workflows/sand-production
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$case_dir/small.toml
# The small scene's material is the case's, unchanged.
mat() { awk '/^\[\[material\]\]/{m=1} /^$/{m=0} m' "$1"; }
[ -n "$(mat "$scene")" ] && diff <(mat "$case_dir/scene.toml") <(mat "$scene") || { echo "FAIL: small.toml's material differs from scene.toml's"; exit 1; }
q="--quiet"
"$bin/gen-primary" --scene "$case_dir/small-generate.toml" --out "$tmp/settled.h5" $q
"$bin/compact" --scene "$case_dir/small-generate.toml" --in "$tmp/settled.h5" --out "$tmp/compacted.h5" $q
"$bin/run-stage" --scene "$scene" --stage load --in "$tmp/compacted.h5" --out "$tmp/loaded.h5" $q
"$bin/run-stage" --scene "$scene" --stage cement --in "$tmp/loaded.h5" --out "$tmp/cemented.h5" $q
"$bin/run-stage" --scene "$scene" --stage drill --in "$tmp/cemented.h5" --out "$tmp/drilled.h5" $q
# Usage: report NOW CEMENTED (checkpoint names under $tmp): the stress around the well against
# Kirsch, the broken bonds and the displacement of NOW, counted from the bonds and positions of CEMENTED.
report() {
  "$bin/post-macro" --in "$tmp/$1.h5" --reference "$tmp/$2.h5" --vtk "$tmp/$1.vtu" $q
  "$py" "$src/../scripts/well_report.py" --stress "$tmp/$1.vtu" --bonds-made "$tmp/$2.h5" --bonds-now "$tmp/$1.h5" \
    --centre 0.14,0.14 --radius 0.035 --sigma0 18e6 --outer 0.126 --bin 0.014 --prefix "$tmp/$1"
}
report drilled cemented
sed -e 's/^cohesion = 635.0 .*/cohesion = 1.0e5/' -e 's/^tensile_strength = 1.3e3 .*/tensile_strength = 1.0e5/' "$scene" > "$tmp/elastic.toml"
[ "$(grep -c '^cohesion = 1.0e5$\|^tensile_strength = 1.0e5$' "$tmp/elastic.toml")" = 2 ] || { echo "FAIL: small.toml's bond strengths not found"; exit 1; }
"$bin/run-stage" --scene "$tmp/elastic.toml" --stage cement --in "$tmp/loaded.h5" --out "$tmp/elastic_cemented.h5" $q
"$bin/run-stage" --scene "$tmp/elastic.toml" --stage drill --in "$tmp/elastic_cemented.h5" --out "$tmp/elastic.h5" $q
report elastic elastic_cemented
"$bin/run-stage" --scene "$scene" --stage produce --in "$tmp/drilled.h5" --out "$tmp/produced.h5" $q
"$bin/run-stage" --scene "$scene" --stage produce_dry --in "$tmp/drilled.h5" --out "$tmp/dry.h5" $q
"$py" - "$tmp" <<'PY'
import csv, sys
tmp = sys.argv[1]
last = lambda p: list(csv.DictReader(open(p)))[-1]
wet, dry = last(f"{tmp}/produced.sink.csv"), last(f"{tmp}/dry.sink.csv")
print(f"produced with the fluid: {wet['removed_total']} grains, {float(wet['removed_mass_kg']):.4g} kg; without: {dry['removed_total']}")
assert int(wet["removed_total"]) > 0, "no sand produced with the fluid on"
assert 4 * int(dry["removed_total"]) <= int(wet["removed_total"]), "as much sand produced without the fluid"
rows = list(csv.DictReader(open(f"{tmp}/drilled_kirsch.csv")))
f = lambda r, k: float(r[k])
first = rows[0]
print(f"first bin r/a = {f(first, 'r_over_a'):.2f}: sigma_tt {f(first, 'stt_Pa') / 1e6:.1f} MPa, sigma_rr {f(first, 'srr_Pa') / 1e6:.1f} MPa")
assert f(first, "stt_Pa") > 3 * f(first, "srr_Pa"), "the hoop stress does not dominate next to the well"
assert all(f(r, "stt_Pa") > f(r, "srr_Pa") for r in rows if f(r, "r_over_a") < 2), "sigma_tt <= sigma_rr within 2a"
b = list(csv.DictReader(open(f"{tmp}/drilled_bonds.csv")))
frac = lambda sel: sum(int(r["broken"]) for r in sel) / max(1, sum(int(r["bonds"]) for r in sel))
near, far = frac([r for r in b if f(r, "r_over_a") < 2]), frac([r for r in b if f(r, "r_over_a") > 2.5])
print(f"broken bonds: {near:.3f} within 2a, {far:.3f} beyond 2.5a")
assert near > 2 * far, "the rock does not yield at the wall"
elastic = [r for r in csv.DictReader(open(f"{tmp}/elastic_kirsch.csv")) if r["checked"] == "1"]
for r in elastic:
    print(f"unbreakable bonds, r/a = {f(r, 'r_over_a'):.2f}: sigma_rr {f(r, 'srr_Pa') / 1e6:.2f} (Kirsch {f(r, 'kirsch_srr_Pa') / 1e6:.2f} "
          f"+- {f(r, 'tol_srr_Pa') / 1e6:.2f}), sigma_tt {f(r, 'stt_Pa') / 1e6:.2f} (Kirsch {f(r, 'kirsch_stt_Pa') / 1e6:.2f} "
          f"+- {f(r, 'tol_stt_Pa') / 1e6:.2f}) MPa")
assert len(elastic) == 3, "the bins at r >= 2a"
assert all(r["within"] == "1" for r in elastic), "the elastic slab's stress misses Kirsch (P83) at r >= 2a"
broken = sum(int(r["broken"]) for r in csv.DictReader(open(f"{tmp}/elastic_bonds.csv")))
assert broken == 0, f"{broken} unbreakable bonds broke"
PY
echo "sand production small: checks passed"
