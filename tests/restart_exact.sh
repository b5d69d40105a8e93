#!/usr/bin/env bash
# A resumed run gives the same bits as an uninterrupted one, also after kill -9 at random moments
# (possibly during a checkpoint write): every dataset is compared bit for bit.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/small.toml
set -e
"$bin/gen-primary" --scene "$scene" --out "$tmp/start.h5" --quiet
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/full.h5" --vtk "$tmp/vtk_full" --quiet
set +e

# 1. Clean stop and resume: periodic checkpoints, then --restart from the newest one.
kills=0
RANDOM=12345
for attempt in $(seq 1 40); do
  "$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/killed.h5" --vtk "$tmp/vtk_killed" \
    --checkpoint-every 700 --restart --quiet &
  pid=$!
  # Let it run a random 0.2-1.2 s, then kill -9 unless it finished.
  sleep "0.$((RANDOM % 10 + 2))"
  if kill -0 $pid 2>/dev/null; then kill -9 $pid; wait $pid 2>/dev/null; kills=$((kills + 1)); else wait $pid; rc=$?; [ $rc -eq 0 ] || { echo "run failed with $rc"; exit 1; }; fi
  [ -e "$tmp/killed.h5" ] && break
done
[ -e "$tmp/killed.h5" ] || { echo "the killed run never finished"; exit 1; }
echo "survived $kills kill -9"
[ $kills -ge 2 ] || { echo "too few kills to test anything ($kills): the stage ran too fast"; exit 1; }
[ -e "$tmp/killed.restart.h5" ] && { echo "periodic checkpoint not removed after completion"; exit 1; }
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/killed.h5" || exit 1
# The VTK series is complete and identical too.
diff -r "$tmp/vtk_full" "$tmp/vtk_killed" > /dev/null || { echo "VTK frames differ after restarts"; exit 1; }

# 2. A changed scene refuses to resume (exactness would be lost).
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/x.h5" --checkpoint-every 500 --quiet &
pid=$!; sleep 0.6; kill -9 $pid; wait $pid 2>/dev/null
if [ -e "$tmp/x.restart.h5" ]; then
  sed 's/restitution = 0.3/restitution = 0.31/' "$scene" > "$tmp/changed.toml"
  "$bin/run-stage" --scene "$tmp/changed.toml" --stage long --in "$tmp/start.h5" --out "$tmp/x.h5" --restart --quiet 2> "$tmp/err"
  rc=$?
  [ $rc -eq 3 ] && grep -q "differs from the one the periodic checkpoint" "$tmp/err" || { echo "changed scene accepted on restart ($rc)"; cat "$tmp/err"; exit 1; }
fi
echo "restart exact"
