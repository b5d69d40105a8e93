#!/usr/bin/env bash
# run-stage --restart continues only the run its periodic checkpoint belongs to (same --in, scene,
# files the scene reads, stage, version), and a checkpoint whose particles lie outside the scene's
# closed box is refused. Ctrl-C (SIGINT) and SIGTERM stop run-stage after the current step with a
# periodic checkpoint and the command that resumes it, exit 130; resumed, the run ends with the
# bits of an uninterrupted one.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/check_lib.sh"  # check NAME EXPECTED_CODE PATTERN -- command...
reseal() {  # after an edit with h5py (docs/checkpoint.md "Editing a checkpoint")
  "$py" -c "
import sys, zlib
data = open(sys.argv[1], 'rb').read(); body = data[512:]
line = b'dem-checkpoint-seal crc32=%08x size=%d\n' % (zlib.crc32(body), len(body))
open(sys.argv[1], 'wb').write(line.ljust(512, b'\0') + body)" "$1"
}
# The test scene, with a stage action that reads an STL file (a mesh region far from the spheres).
cp "$src/data/cube.stl" "$tmp/region.stl"
{ cat "$src/data/small.toml"; printf '\n[[stage.action]]\ntype = "remove"\nregion = { type = "mesh", file = "region.stl", translate = [5.0, 0.0, 0.0] }\n'; } > "$tmp/scene.toml"
scene=$tmp/scene.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/a.h5" --quiet > /dev/null || exit 1
sed 's/^seed = 7/seed = 8/' "$scene" > "$tmp/seed8.toml"
"$bin/gen-primary" --scene "$tmp/seed8.toml" --out "$tmp/b.h5" --quiet > /dev/null || exit 1

# A periodic checkpoint of stage long from a.h5: the run is killed once it has one.
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/a.h5" --out "$tmp/r.h5" --checkpoint-every 200 --quiet 2> /dev/null &
pid=$!
until [ -e "$tmp/r.restart.h5" ]; do kill -0 $pid 2> /dev/null || break; sleep 0.05; done
sleep 0.05; kill -9 $pid 2> /dev/null; wait $pid 2> /dev/null
[ -e "$tmp/r.restart.h5" ] && [ ! -e "$tmp/r.h5" ] || { echo "FAIL no periodic checkpoint to test with"; exit 1; }
cp "$tmp/r.restart.h5" "$tmp/saved.restart.h5"
resume() { "$bin/run-stage" --scene "$1" --stage long --in "$2" --out "$tmp/r.h5" --checkpoint-every 200 --restart --quiet; }

check "restart from another --in refused" 3 "r.restart.h5 was started from a different input: --in .*a.h5 (crc32=.*) then, --in .*b.h5 (crc32=.*) now (to start the stage over from --in, delete .*r.restart.h5" -- resume "$scene" "$tmp/b.h5"
echo "not a checkpoint" > "$tmp/text.h5"
check "restart with an unreadable --in refused" 3 "cannot be read to compare" -- resume "$scene" "$tmp/text.h5"
check "restart with --in missing refused" 2 "--in: File does not exist" -- resume "$scene" "$tmp/none.h5"
sed 's/ 10/ 11/g' "$src/data/cube.stl" > "$tmp/region.stl"  # a larger cube
check "restart after a file the scene reads changed refused" 3 "the file .*region.stl the scene reads held other bytes (fnv1a64=" -- resume "$scene" "$tmp/a.h5"
cp "$src/data/cube.stl" "$tmp/region.stl"
check "restart of another stage refused" 3 'belongs to stage "long", not "shake"' -- \
  "$bin/run-stage" --scene "$scene" --stage shake --in "$tmp/a.h5" --out "$tmp/r.h5" --restart --quiet
"$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r+'); f.attrs.modify('writer_version', b'0.0.9')" "$tmp/r.restart.h5" && reseal "$tmp/r.restart.h5"
check "restart written by another version refused" 3 "was written by run-stage 0.0.9, this is" -- resume "$scene" "$tmp/a.h5"
cp "$tmp/saved.restart.h5" "$tmp/r.restart.h5"
"$py" -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r+'); del f['run/input_seal']" "$tmp/r.restart.h5" && reseal "$tmp/r.restart.h5"
check "restart that does not record its input refused" 3 "does not record the --in checkpoint" -- resume "$scene" "$tmp/a.h5"
cmp -s "$tmp/saved.restart.h5" "$tmp/r.restart.h5" && { echo "FAIL the edit did not change the file"; fail=1; }
cp "$tmp/saved.restart.h5" "$tmp/r.restart.h5"
[ -e "$tmp/r.h5" ] && { echo "FAIL output written by a refused restart"; fail=1; }
check "restart with a scene whose values changed refused" 3 "was written with another scene: the scene file .*seed8.toml holds other values" -- resume "$tmp/seed8.toml" "$tmp/a.h5"
# The same values with a comment added, blank lines and spacing changed: the same run, resumed,
# with the bits of an uninterrupted one.
{ echo "# a note added while the run was stopped"; echo; sed 's/^\([a-z_]*\) = /\1   =   /' "$scene"; echo "# end"; } > "$tmp/commented.toml"
cmp -s "$scene" "$tmp/commented.toml" && { echo "FAIL the commented scene is the same text"; fail=1; }
check "restart with only comments and layout changed accepted" 0 "only in comments and layout (the same values): resuming" -- \
  "$bin/run-stage" --scene "$tmp/commented.toml" --stage long --in "$tmp/a.h5" --out "$tmp/r.h5" --checkpoint-every 200 --restart
"$bin/run-stage" --scene "$scene" --stage long --in "$tmp/a.h5" --out "$tmp/whole.h5" --quiet || exit 1
"$py" -c "
import h5py, sys, numpy as np
a, b = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
for k in ('position', 'velocity', 'angular_velocity'):
    if not np.array_equal(a['particles/' + k][...], b['particles/' + k][...]): sys.exit('particles/' + k + ' differ')
" "$tmp/r.h5" "$tmp/whole.h5" || { echo "FAIL the run resumed with a commented scene is not the uninterrupted one"; fail=1; }
rm -f "$tmp/r.h5"
cp "$tmp/saved.restart.h5" "$tmp/r.restart.h5"
check "restart of the same run accepted" 0 "resuming stage long at step" -- \
  "$bin/run-stage" --scene "$scene" --stage long --in "$tmp/a.h5" --out "$tmp/r.h5" --checkpoint-every 200 --restart
[ -e "$tmp/r.h5" ] && [ ! -e "$tmp/r.restart.h5" ] || { echo "FAIL the resumed run did not finish"; fail=1; }

# Particles outside the scene's closed box: the box renamed and moved 1 m along x is refused (the
# scene's walls hold none of them); moved under the same name, the checkpoint's box is kept: a warning.
sed 's/^min = \[0.0, 0.0, 0.0\]/min = [1.0, 0.0, 0.0]/; s/^max = \[0.02, 0.02, 0.05\]/max = [1.02, 0.02, 0.05]/' "$src/data/small.toml" > "$tmp/moved.toml"
sed 's/^name = "box"/name = "crate"/; s/^wall = "box/wall = "crate/' "$tmp/moved.toml" > "$tmp/crate.toml"
check "checkpoint outside the scene's box refused" 3 "a.h5: \\([0-9][0-9]*\\) of \\1 particles lie outside the closed box \"crate\" of .*crate.toml, beyond its face crate.xmin (e.g. particle id [0-9]* at \[.*\] m, its centre 0.9[0-9]* m beyond the face): the checkpoint does not belong to this scene" -- \
  "$bin/run-stage" --scene "$tmp/crate.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/c.h5" --quiet
[ -e "$tmp/c.h5" ] && { echo "FAIL output written for a checkpoint outside the box"; fail=1; }
check "box of the same name moved: warned" 0 "warning: .*a.h5: \\([0-9][0-9]*\\) of \\1 particles lie outside the closed box \"box\" as .*moved.toml places it, beyond its face box.xmin .*; the run keeps the box where the checkpoint left it" -- \
  "$bin/run-stage" --scene "$tmp/moved.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/m.h5" --quiet
check "particles inside: no warning" 0 "removed [0-9][0-9]* particles" -- "$bin/run-stage" --scene "$src/data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/s.h5" --quiet
grep -q warning "$tmp/out" && { echo "FAIL a warning for particles inside the box"; cat "$tmp/out"; fail=1; }

# Ctrl-C: a run with no periodic checkpoint due (every 100,000 steps) stops after the current step,
# writes one and prints the command to resume. (A script's background jobs ignore SIGINT unless job
# control is on: set -m. Where this shell was started with SIGINT ignored, SIGTERM stands in.)
set -m
sig=INT
[ $(( 0x$(awk '/^SigIgn/ { print $2 }' /proc/$$/status) & 2 )) -ne 0 ] && { sig=TERM; echo "note: SIGINT is ignored here; SIGTERM instead"; }
stage_args=(--scene "$src/data/small.toml" --stage long --in "$tmp/a.h5")
"$bin/run-stage" "${stage_args[@]}" --out "$tmp/full.h5" --vtk "$tmp/vtk_full" --wall-forces "$tmp/full.csv" --quiet || exit 1
"$bin/run-stage" "${stage_args[@]}" --out "$tmp/int.h5" --vtk "$tmp/vtk_int" --wall-forces "$tmp/int.csv" --checkpoint-every 100000 --quiet > "$tmp/int.out" 2>&1 &
pid=$!
until [ -e "$tmp/vtk_int/long.partial/long_particles.pvd" ]; do kill -0 $pid 2> /dev/null || break; sleep 0.05; done
sleep 0.5; kill -$sig $pid; wait $pid; rc=$?
set +m
if [ $rc -ne 130 ] || ! grep -q "run-stage: interrupted by SIG$sig.* after step [0-9]* ([0-9]* of [0-9]* steps of stage long, t = .* s); the periodic checkpoint .*int.restart.h5 holds step [0-9]*. To resume, run:" "$tmp/int.out"; then
  echo "FAIL SIG$sig: exit $rc (want 130):"; cat "$tmp/int.out"; fail=1
else echo "ok   SIG$sig stops after a step with a periodic checkpoint, exit 130"; fi
[ -e "$tmp/int.restart.h5" ] && [ ! -e "$tmp/int.h5" ] && [ ! -e "$tmp/vtk_int/long_particles.pvd" ] || { echo "FAIL after SIG$sig: want the periodic checkpoint, no output, no frames in place"; ls -R "$tmp"; fail=1; }
resume_cmd=$(grep -A1 "To resume, run:" "$tmp/int.out" | tail -1)
case "$resume_cmd" in *" --restart") ;; *) echo "FAIL the resume command lacks --restart: $resume_cmd"; fail=1 ;; esac
bash -c "$resume_cmd" > "$tmp/resumed.out" 2>&1 || { echo "FAIL the printed command did not resume:"; cat "$tmp/resumed.out"; fail=1; }
"$py" "$src/compare_checkpoints.py" "$tmp/full.h5" "$tmp/int.h5" > /dev/null || { echo "FAIL resumed after SIG$sig: differs from the uninterrupted run"; fail=1; }
diff -r "$tmp/vtk_full" "$tmp/vtk_int" > /dev/null || { echo "FAIL VTK frames differ after SIG$sig"; fail=1; }
cmp -s "$tmp/full.csv" "$tmp/int.csv" || { echo "FAIL wall force CSV differs after SIG$sig"; fail=1; }
[ -e "$tmp/int.restart.h5" ] && { echo "FAIL periodic checkpoint left after the resumed run"; fail=1; }
[ $fail -eq 0 ] && echo "ok   resumed after SIG$sig: the same bits, frames and CSV as the uninterrupted run"

# SIGTERM with periodic checkpoints off: nothing to resume, nothing left behind, exit 130.
"$bin/run-stage" "${stage_args[@]}" --out "$tmp/term.h5" --vtk "$tmp/vtk_term" --wall-forces "$tmp/term.csv" --checkpoint-minutes 0 --quiet > "$tmp/term.out" 2>&1 &
pid=$!
until [ -e "$tmp/vtk_term/long.partial/long_particles.pvd" ]; do kill -0 $pid 2> /dev/null || break; sleep 0.05; done
sleep 0.3; kill -TERM $pid; wait $pid; rc=$?
if [ $rc -ne 130 ] || ! grep -q "interrupted by SIGTERM .* no periodic checkpoint (--checkpoint-minutes 0 and no --checkpoint-every), nothing written" "$tmp/term.out"; then
  echo "FAIL SIGTERM without periodic checkpoints: exit $rc (want 130):"; cat "$tmp/term.out"; fail=1
else echo "ok   SIGTERM without periodic checkpoints: exit 130, says nothing was written"; fi
left=$(find "$tmp/vtk_term" -type f 2> /dev/null; ls "$tmp"/term*.partial "$tmp"/term.restart.h5 "$tmp"/term.h5 2> /dev/null)
[ -z "$left" ] || { echo "FAIL left behind after SIGTERM: $left"; fail=1; }
exit $fail
