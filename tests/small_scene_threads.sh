#!/usr/bin/env bash
# A scene below the tools' cut-off (2,000 particles; here 120) steps on one thread unless the user
# chose the thread count (--threads N or OMP_NUM_THREADS), and the bits are the same either way.
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
exit $fail
