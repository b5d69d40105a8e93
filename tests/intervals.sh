#!/usr/bin/env bash
# Intervals in steps or seconds, on the command line and in the scene alike (docs/scene.md,
# "Intervals"), on the free fall of tests/data/health_fall.toml (health_every = 0.004 s):
# 1. the health log is the same, byte for byte, with the scene's 0.004 s, the scene's "K steps",
#    --health-every K and --health-every 0.004s, where K = round(0.004 / dt);
# 2. bad intervals are refused with the option or key, the value and what is allowed (exit 2 on
#    the command line, 3 in the scene), leaving nothing behind.
set -uo pipefail  # not -e: check() looks at failing commands' exit codes
bin=$1 src=$(cd "$2" && pwd) py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$src/check_lib.sh"
fall=$src/data/health_fall.toml
run() { "$bin/run-stage" --stage fall --in "$tmp/start.h5" --quiet "$@"; }

"$bin/gen-primary" --scene "$fall" --out "$tmp/start.h5" --quiet || exit 1
run --scene "$fall" --out "$tmp/scene_s.h5" || exit 1
dt=$("$py" -c "import csv, sys; print(next(csv.DictReader(open(sys.argv[1])))['dt_s'])" "$tmp/scene_s.health.csv")
k=$("$py" -c "print(max(1, round(0.004 / $dt)))")
echo "dt = $dt s: 0.004 s is $k steps"
sed "s/^health_every = 0.004/health_every = \"$k steps\"/" "$fall" > "$tmp/steps.toml"
run --scene "$tmp/steps.toml" --out "$tmp/scene_steps.h5" || exit 1
run --scene "$fall" --out "$tmp/cli_steps.h5" --health-every "$k" || exit 1
run --scene "$fall" --out "$tmp/cli_s.h5" --health-every 0.004s || exit 1
for f in scene_steps cli_steps cli_s; do
  cmp "$tmp/scene_s.health.csv" "$tmp/$f.health.csv" && echo "ok   $f: the same health log" || { echo "FAIL $f: another health log"; fail=1; }
done

check "--health-every 2.5 (not whole steps)" 2 "whole number of steps" -- run --scene "$fall" --out "$tmp/bad.h5" --health-every 2.5
check "--checkpoint-every 10q" 2 "checkpoint-every.*expected steps or seconds" -- run --scene "$fall" --out "$tmp/bad.h5" --checkpoint-every 10q
check "--track-every 0" 2 "must be > 0" -- run --scene "$fall" --out "$tmp/bad.h5" --track /dev/null --track-ids 0 --track-every 0
sed 's/^health_every = 0.004/health_every = "0.5 steps"/' "$fall" > "$tmp/half.toml"
check "health_every = \"0.5 steps\"" 3 "half.toml:.*health_every = \"0.5 steps\": a whole number of steps" -- run --scene "$tmp/half.toml" --out "$tmp/bad.h5"
sed 's/^health_every = 0.004/health_every = "4 ms"/' "$fall" > "$tmp/ms.toml"
check "health_every = \"4 ms\"" 3 "ms.toml:.*health_every.*\"0.01 s\"" -- run --scene "$tmp/ms.toml" --out "$tmp/bad.h5"
[ ! -e "$tmp/bad.h5" ] && [ ! -e "$tmp/bad.health.csv" ] || { echo "FAIL: a refused run left outputs"; fail=1; }
exit $fail
