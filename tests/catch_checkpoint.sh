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
