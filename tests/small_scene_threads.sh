#!/usr/bin/env bash
# A scene below the tools' cut-off (2,000 particles; here 120) steps on one thread unless the user
# chose the thread count (--threads N or OMP_NUM_THREADS), and the bits are the same either way;
# one above it (2,100) steps on all the machine's cores with no choice made.
# (Both sides of the cut-off inside the library: Determinism.SmallScenesStepOnOneThreadWithTheSameBits.)
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/check_lib.sh"  # check NAME EXPECTED_CODE PATTERN -- command...
scene=$src/data/small.toml
env -u OMP_NUM_THREADS "$bin/gen-primary" --scene "$scene" --out "$tmp/a.h5" --quiet > /dev/null || exit 1
# run-stage's stage `shake` with the environment change $1 (env's -u NAME or NAME=VALUE), then the rest.
stage() {
  local change=$1; shift
  env $change "$bin/run-stage" --scene "$scene" --stage shake --in "$tmp/a.h5" --checkpoint-minutes 0 "$@"
}
check "no thread count chosen: one thread" 0 "particle-steps/s on 1 thread" -- stage "-u OMP_NUM_THREADS" --out "$tmp/default.h5"
check "--threads 2: two threads" 0 "particle-steps/s on 2 threads" -- stage "-u OMP_NUM_THREADS" --out "$tmp/flag.h5" --threads 2
check "OMP_NUM_THREADS=2: two threads" 0 "particle-steps/s on 2 threads" -- stage OMP_NUM_THREADS=2 --out "$tmp/env.h5"
for other in flag env; do
  "$py" "$src/compare_checkpoints.py" "$tmp/default.h5" "$tmp/$other.h5" > /dev/null || { echo "FAIL one thread and two ($other) differ"; fail=1; }
done
[ $fail -eq 0 ] && echo "ok   the same bits on one thread and on two"
# Above the cut-off: small.toml with 2,100 spheres of half the radius, a few hundred steps of
# settling and shaking, its particle-removing action dropped (it would end the stage below 2,000).
big=$tmp/big.toml
sed -e 's/^count = 120$/count = 2100/' -e 's/^radius_min = 0.0016$/radius_min = 0.0008/' -e 's/^radius_max = 0.0020$/radius_max = 0.0010/' \
    -e 's/^max_time = 0.3$/max_time = 0.001/' -e 's/^check_every = 0.01$/check_every = 0.001/' \
    -e 's/^duration = 0.03$/duration = 0.0005/' -e 's/^output_every = 0.01$/output_every = 0.0005/' "$scene" |
  awk '/^type = "remove"$/ { exit } NR > 1 { print last } { last = $0 }' > "$big"
grep -q 'count = 2100' "$big" && ! grep -q '"remove"' "$big" || { echo "FAIL the scene above the cut-off was not made"; exit 1; }
env -u OMP_NUM_THREADS "$bin/gen-primary" --scene "$big" --out "$tmp/big.h5" --quiet > /dev/null || exit 1
cores=$(env -u OMP_NUM_THREADS nproc)
if [ "$cores" -ge 2 ]; then
  check "2,100 spheres, no thread count chosen: all $cores cores" 0 "particle-steps/s on $cores threads" -- \
    env -u OMP_NUM_THREADS "$bin/run-stage" --scene "$big" --stage shake --in "$tmp/big.h5" --out "$tmp/big_all.h5" --checkpoint-minutes 0
  check "2,100 spheres, --threads 1: one thread" 0 "particle-steps/s on 1 thread" -- \
    env -u OMP_NUM_THREADS "$bin/run-stage" --scene "$big" --stage shake --in "$tmp/big.h5" --out "$tmp/big_one.h5" --checkpoint-minutes 0 --threads 1
  "$py" "$src/compare_checkpoints.py" "$tmp/big_all.h5" "$tmp/big_one.h5" > /dev/null || { echo "FAIL 2,100 spheres: one thread and all differ"; fail=1; }
else
  echo "skip 2,100 spheres on all cores: this machine has one"
fi
exit $fail
