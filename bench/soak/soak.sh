#!/usr/bin/env bash
# Soak test (issue 10, README "Reliability"; not in CI): gen-primary pours and settles a
# 100,000-sphere bed (before the clock starts), then run-stage shakes it for
# MINUTES (default 60) with a periodic checkpoint every CHECKPOINT steps, killed with SIGKILL at
# random moments 8-20 minutes apart and restarted with --restart each time. Samples the resident
# memory every 5 s and checks at the end that
#   - every restart resumed from the newest periodic checkpoint (the step it printed is the step
#     that checkpoint holds, and no earlier than the previous restart's),
#   - the newest checkpoint is complete and readable (post-macro reads it) with every particle,
#   - the resident memory does not grow: within each run segment that starts after the first third
#     of the soak and lives two vibration cycles past its first minute, the 90th percentile of the
#     memory over its last cycle is within 5 % of that over the cycle before (soak_report.py says
#     why whole cycles: the shaken bed's lists breathe with the cycle).
# Writes OUT/gen.log (the settled bed), OUT/memory.csv (seconds, segment, pid, step, rss_kb), OUT/restarts.csv and OUT/soak.txt.
#   bench/soak/soak.sh [MINUTES] [THREADS] [OUT]      (build first: make -f Makefile.cases build)
# A short smoke run on a smaller scene: SOAK_SCENE=scene.toml SOAK_LIFE_MIN=30 SOAK_LIFE_MAX=60 CHECKPOINT=2000
# SOAK_BED=OUT/poured.h5 of an earlier soak of the same scene skips the settle (~15 min on 2 cores).
set -u
minutes=${1:-60} threads=${2:-0} out=${3:-out/soak}
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$root/build/tools scene=${SOAK_SCENE:-$root/bench/soak/scene.toml}
checkpoint=${CHECKPOINT:-20000}           # steps: ~2-3 minutes at 100,000 spheres on 2 cores
life_min=${SOAK_LIFE_MIN:-480} life_max=${SOAK_LIFE_MAX:-1200}  # seconds between kills
count=$(sed -n 's/^count = \([0-9]*\).*/\1/p' "$scene")
frequency=$(sed -n 's/^frequency = \([0-9.eE+-]*\).*/\1/p' "$scene" | head -1)  # of the shaking, Hz
mkdir -p "$out"
rm -f "$out"/shake.h5 "$out"/shake.restart.h5
echo "seconds,segment,pid,step,rss_kb" > "$out/memory.csv"
echo "segment,started_s,resumed_step,checkpoint_step_before,killed_s" > "$out/restarts.csv"
RANDOM=2026
if [ -n "${SOAK_BED:-}" ]; then
  [ "$(cd "$(dirname "$SOAK_BED")" && pwd)/$(basename "$SOAK_BED")" = "$(cd "$out" && pwd)/poured.h5" ] || cp "$SOAK_BED" "$out/poured.h5"
  echo "bed reused from $SOAK_BED: $count particles" > "$out/gen.log"
else
  "$bin/gen-primary" --scene "$scene" --out "$out/poured.h5" --threads "$threads" > "$out/gen.log" 2>&1 || { cat "$out/gen.log"; exit 1; }
fi
t0=$(date +%s) end=$(( $(date +%s) + minutes * 60 )) segment=0 fail=0 last_resume=-1
ckpt_step() {  # the step a checkpoint holds, or -1
  /usr/bin/python3 -c "import h5py,sys; print(int(h5py.File(sys.argv[1],'r')['state/step'][()]))" "$1" 2>/dev/null || echo -1
}
while [ "$(date +%s)" -lt "$end" ]; do
  segment=$((segment + 1))
  before=-1; [ -e "$out/shake.restart.h5" ] && before=$(ckpt_step "$out/shake.restart.h5")
  started=$(( $(date +%s) - t0 ))
  "$bin/run-stage" --scene "$scene" --stage shake --in "$out/poured.h5" --out "$out/shake.h5" --threads "$threads" \
    --checkpoint-every "$checkpoint" --restart > "$out/segment_$segment.log" 2>&1 &
  pid=$!
  life=$(( life_min + RANDOM % (life_max - life_min + 1) )); stop=$(( $(date +%s) + life )); [ "$stop" -gt "$end" ] && stop=$end
  while kill -0 "$pid" 2> /dev/null && [ "$(date +%s)" -lt "$stop" ]; do
    rss=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2> /dev/null || echo "")
    [ -n "$rss" ] && echo "$(( $(date +%s) - t0 )),$segment,$pid,$(ckpt_step "$out/shake.restart.h5"),$rss" >> "$out/memory.csv"
    sleep 5
  done
  kill -9 "$pid" 2> /dev/null; wait "$pid" 2> /dev/null
  resumed=$(sed -n 's/.*resuming stage shake at step \([0-9]*\).*/\1/p' "$out/segment_$segment.log")
  echo "$segment,$started,${resumed:--1},$before,$(( $(date +%s) - t0 ))" >> "$out/restarts.csv"
  if [ "$before" -ge 0 ] && [ "${resumed:--1}" != "$before" ]; then
    echo "FAIL segment $segment resumed at step ${resumed:-none}, the newest checkpoint held $before"; fail=1
  fi
  if [ "${resumed:--1}" -ge 0 ] && [ "$resumed" -lt "$last_resume" ]; then echo "FAIL segment $segment went back to step $resumed"; fail=1; fi
  [ "${resumed:--1}" -ge 0 ] && last_resume=$resumed
done
final=$(ckpt_step "$out/shake.restart.h5")
if ! "$bin/post-macro" --reference "$out/poured.h5" --in "$out/shake.restart.h5" --vtk "$out/final.vtu" > "$out/post.log" 2>&1; then
  echo "FAIL the newest checkpoint is not readable"; cat "$out/post.log"; fail=1
fi
particles=$(/usr/bin/python3 -c "import h5py,sys,numpy as np; f=h5py.File(sys.argv[1],'r'); x=f['particles/position'][()]; print(len(x) if np.isfinite(x).all() else -1)" "$out/shake.restart.h5")
[ "$particles" = "$count" ] || { echo "FAIL the newest checkpoint holds $particles finite particles, not $count"; fail=1; }
{ echo "soak: start: $(grep -m1 'particles' "$out/gen.log")"
  /usr/bin/python3 "$root/bench/soak/soak_report.py" "$out" "$fail" "$minutes" "$final" "$particles" "$frequency"; } | tee "$out/soak.txt"
exit "${PIPESTATUS[0]}"
