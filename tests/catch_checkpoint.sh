# Sourced by the restart tests: catch_checkpoint RESTART COPY -- command... runs the command (a
# run-stage writing periodic checkpoints to RESTART) in the background, copies the first checkpoint
# to COPY as soon as it appears (it appears by rename, so complete), waits for the run to end, and
# fails the test unless a copy was caught before the stage ended.
catch_checkpoint() {
  local restart=$1 copy=$2; shift 3
  "$@" &
  local pid=$!
  until [ -e "$restart" ] || ! kill -0 $pid 2> /dev/null; do sleep 0.002; done
  cp "$restart" "$copy" 2> /dev/null || true
  wait $pid
  [ -e "$copy" ] || { echo "FAIL: no periodic checkpoint seen before the stage ended"; exit 1; }
}

# full_and_cut SCENE STAGE EVERY (with bin, src, py and tmp set as the restart tests set them):
# start.h5 from gen-primary; full.h5 from the stage run uninterrupted on one thread (its messages in
# full.log); cut.h5 from the same run on two threads writing a periodic checkpoint every EVERY
# steps, the first caught as mid.h5. Fails unless cut.h5 equals full.h5.
full_and_cut() {
  local scene=$1 stage=$2 every=$3
  "$bin/gen-primary" --scene "$scene" --out "$tmp/start.h5" --quiet
  OMP_NUM_THREADS=1 "$bin/run-stage" --scene "$scene" --stage "$stage" --in "$tmp/start.h5" --out "$tmp/full.h5" 2> "$tmp/full.log"
  catch_checkpoint "$tmp/cut.restart.h5" "$tmp/mid.h5" -- env OMP_NUM_THREADS=2 "$bin/run-stage" --scene "$scene" --stage "$stage" \
    --in "$tmp/start.h5" --out "$tmp/cut.h5" --checkpoint-every "$every" --quiet
  "$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/cut.h5" > /dev/null || { echo "FAIL: two threads differ from one"; exit 1; }
}
