#!/usr/bin/env bash
# A resumed run gives the same bits as an uninterrupted one, also after kill -9 at random moments
# (possibly during a checkpoint write): every dataset is compared bit for bit.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/small.toml
set -e
"$bin/gen-primary" --scene "$scene" --out "$tmp/start.h5" --quiet
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/full.h5" --vtk "$tmp/vtk_full" \
  --wall-forces "$tmp/full.csv" --wall-forces-every 50 --track "$tmp/full_track.csv" --track-ids 0,7 --track-every 30 --quiet
set +e

# 1. kill -9 at 20 random moments (periodic checkpoints every 300 steps, so some kills land
#    during a checkpoint write), resuming with --restart each time, then run to the end.
kills=0 during_write=0
RANDOM=12345
for attempt in $(seq 1 100); do
  "$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/killed.h5" --vtk "$tmp/vtk_killed" \
    --wall-forces "$tmp/killed.csv" --wall-forces-every 50 --track "$tmp/killed_track.csv" --track-ids 0,7 --track-every 30 \
    --checkpoint-every 300 --restart --quiet 2> /dev/null &
  pid=$!
  if [ $kills -lt 20 ]; then
    sleep "0.$((RANDOM % 35 + 10))"
    if kill -0 $pid 2> /dev/null; then
      kill -9 $pid; wait $pid 2> /dev/null; kills=$((kills + 1))
      [ -e "$tmp/killed.restart.h5.tmp" ] && during_write=$((during_write + 1))
      # The newest periodic checkpoint is always complete and readable.
      if [ -e "$tmp/killed.restart.h5" ]; then "$py" -c "import h5py, sys; h5py.File(sys.argv[1], 'r')['particles/position'][()]" "$tmp/killed.restart.h5" || exit 1; fi
      continue
    fi
  fi
  wait $pid; rc=$?
  [ $rc -eq 0 ] || { echo "run failed with $rc"; exit 1; }
  [ -e "$tmp/killed.h5" ] && break
done
[ -e "$tmp/killed.h5" ] || { echo "the killed run never finished"; exit 1; }
echo "survived $kills kill -9 ($during_write during a checkpoint write)"
[ $kills -ge 20 ] || { echo "too few kills to test anything ($kills): the stage ran too fast"; exit 1; }
[ -e "$tmp/killed.restart.h5" ] && { echo "periodic checkpoint not removed after completion"; exit 1; }
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/killed.h5" || exit 1
# The VTK series is complete and identical too.
diff -r "$tmp/vtk_full" "$tmp/vtk_killed" > /dev/null || { echo "VTK frames differ after restarts"; exit 1; }
# So is the per-wall force log (rows after a resumed checkpoint are dropped and written again).
cmp "$tmp/full.csv" "$tmp/killed.csv" || { echo "wall force CSV differs after restarts"; exit 1; }
cmp "$tmp/full_track.csv" "$tmp/killed_track.csv" || { echo "particle track CSV differs after restarts"; exit 1; }
[ "$(wc -l < "$tmp/full_track.csv")" -gt 10 ] || { echo "particle track CSV too short"; exit 1; }

# 1b. The lid servo's integral action is carried over: killed (whatever the machine's speed) once
#     the periodic checkpoint holds the lid pressing with its integral under way, then resumed.
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/pi.h5" --checkpoint-every 300 --quiet &
pid=$!
under_way() {
  "$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); sys.exit(0 if f['run/servo_integral'][0] != 0 else 1)" "$1" 2> /dev/null
}
until [ -e "$tmp/pi.restart.h5" ] && under_way "$tmp/pi.restart.h5"; do kill -0 $pid 2> /dev/null || break; sleep 0.2; done
kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null
[ -e "$tmp/pi.h5" ] && { echo "the stage ended before the servo's integral was under way in a checkpoint"; exit 1; }
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/pi.h5" --checkpoint-every 300 --restart --quiet || exit 1
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/pi.h5" > /dev/null || { echo "resumed with the servo's integral under way: differs"; exit 1; }
echo "resumed exactly with the servo's integral under way"

# 2. A changed scene refuses to resume (exactness would be lost).
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/start.h5" --out "$tmp/x.h5" --checkpoint-every 500 --quiet &
pid=$!; sleep 0.6; kill -9 $pid; wait $pid 2>/dev/null
if [ -e "$tmp/x.restart.h5" ]; then
  sed 's/restitution = 0.3/restitution = 0.31/' "$scene" > "$tmp/changed.toml"
  "$bin/run-stage" --scene "$tmp/changed.toml" --stage long --in "$tmp/start.h5" --out "$tmp/x.h5" --restart --quiet 2> "$tmp/err"
  rc=$?
  [ $rc -eq 3 ] && grep -q "holds other values than the one the periodic checkpoint holds" "$tmp/err" || { echo "changed scene accepted on restart ($rc)"; cat "$tmp/err"; exit 1; }
fi
# 3. A stage with a fluid (upward flow through the settled bed): its void fractions, updated every
#    37 steps, come from the periodic checkpoint (written every 1,000 steps, never at an update), so
#    the resumed run equals the uninterrupted one bit for bit only if the checkpoint holds them.
cp "$scene" "$tmp/fluid.toml"
cat >> "$tmp/fluid.toml" << 'EOF'

[[stage]]
name = "fluid"
duration = 0.1

[stage.fluid]
flow = "uniform"
viscosity = 1.0e-3
density = 998.0
void_cutoff = 0.01
void_every = 37
pressure_gradient = [0.0, 0.0, -6000.0]
EOF
"$bin/run-stage" --scene "$tmp/fluid.toml" --stage fluid --in "$tmp/start.h5" --out "$tmp/fluid_full.h5" --quiet || exit 1
"$bin/run-stage" --scene "$tmp/fluid.toml" --stage fluid --in "$tmp/start.h5" --out "$tmp/fluid_killed.h5" --checkpoint-every 1000 --quiet &
pid=$!
until [ -e "$tmp/fluid_killed.restart.h5" ]; do kill -0 $pid 2> /dev/null || break; sleep 0.05; done
kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null
[ -e "$tmp/fluid_killed.h5" ] && { echo "the fluid stage ended before its first periodic checkpoint"; exit 1; }
"$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); sys.exit(0 if f['particles/void_fraction'].shape[0] == f['particles/id'].shape[0] else 1)" \
  "$tmp/fluid_killed.restart.h5" || { echo "the fluid stage's checkpoint holds no void fractions"; exit 1; }
"$bin/run-stage" --scene "$tmp/fluid.toml" --stage fluid --in "$tmp/start.h5" --out "$tmp/fluid_killed.h5" --checkpoint-every 1000 --restart --quiet || exit 1
"$py" "$src/compare_checkpoints.py" "$tmp/fluid_full.h5" "$tmp/fluid_killed.h5" || { echo "fluid stage: resumed run differs"; exit 1; }
echo "fluid stage resumed exactly"
echo "restart exact"
