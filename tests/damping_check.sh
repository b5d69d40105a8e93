#!/usr/bin/env bash
# The damping-check workflow (thesis §2.4) end to end: a sphere released on a wall follows the exact
# damped oscillator (scripts/damping_check.py --check: within 1 % of g/ω_d, the explicit scheme's
# own error O(γ·ω·Δt + (ω·Δt)²) with ω·Δt ≈ 0.01) and, for restitution 0.5, each half swing's
# velocity amplitude is 0.5 times the previous one (within 0.5 %: the same error on a ratio).
set -eu
bin=$1 src=$2 py=$3 root=$(dirname "$2")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for case in eta_0.5 eta_1e-7; do
  scene=$root/workflows/damping-check/$case.toml
  "$bin/gen-primary" --scene "$scene" --out "$tmp/$case.h5" --quiet > /dev/null
  "$bin/run-stage" --scene "$scene" --stage drop --in "$tmp/$case.h5" --out "$tmp/${case}_end.h5" \
    --track "$tmp/$case.csv" --track-ids 0 --track-every 1 --quiet
  "$py" "$root/scripts/damping_check.py" --checkpoint "$tmp/$case.h5" --track "$tmp/$case.csv" \
    --summary "$tmp/$case.summary.csv" --png "$tmp/$case.png" --check 0.01
  [ -s "$tmp/$case.png" ]
done
ratio=$(grep '^ratio_of_successive_half_swings,' "$tmp/eta_0.5.summary.csv" | cut -d, -f2)
"$py" -c "import sys; r = float(sys.argv[1]); sys.exit(0 if abs(r - 0.5) <= 0.0025 else 'half-swing ratio %g, expected 0.5' % r)" "$ratio"
echo "half-swing ratio $ratio (restitution 0.5)"
