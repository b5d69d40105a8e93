#!/usr/bin/env bash
# run-stage --restart continues only the run its periodic checkpoint belongs to (same --in, scene,
# files the scene reads, stage, version), and a checkpoint whose particles lie outside the scene's
# closed box is refused.
set -u
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
check() {  # check NAME EXPECTED_CODE PATTERN -- command...
  local name=$1 want=$2 pattern=$3; shift 4
  "$@" > "$tmp/out" 2>&1; local got=$?
  if [ "$got" != "$want" ] || ! grep -q -- "$pattern" "$tmp/out"; then
    echo "FAIL $name: exit $got (want $want), pattern '$pattern' in:"; sed 's/^/    /' "$tmp/out"; fail=1
  else echo "ok   $name"; fi
}
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
check "restart with --in missing refused" 3 "cannot be read to compare" -- resume "$scene" "$tmp/none.h5"
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
check "restart of the same run accepted" 0 "resuming stage long at step" -- \
  "$bin/run-stage" --scene "$scene" --stage long --in "$tmp/a.h5" --out "$tmp/r.h5" --checkpoint-every 200 --restart
[ -e "$tmp/r.h5" ] && [ ! -e "$tmp/r.restart.h5" ] || { echo "FAIL the resumed run did not finish"; fail=1; }

# Particles outside the scene's closed box: the box renamed and moved 1 m along x is refused (the
# scene's walls hold none of them); moved under the same name, the checkpoint's box is kept: a warning.
sed 's/^min = \[0.0, 0.0, 0.0\]/min = [1.0, 0.0, 0.0]/; s/^max = \[0.02, 0.02, 0.05\]/max = [1.02, 0.02, 0.05]/' "$src/data/small.toml" > "$tmp/moved.toml"
sed 's/^name = "box"/name = "crate"/; s/^wall = "box/wall = "crate/' "$tmp/moved.toml" > "$tmp/crate.toml"
check "checkpoint outside the scene's box refused" 3 "a.h5: 86 of 86 particles lie outside the closed box \"crate\" of .*crate.toml, beyond its face crate.xmin (e.g. particle id [0-9]* at \[.*\] m, its centre 0.9[0-9]* m beyond the face): the checkpoint does not belong to this scene" -- \
  "$bin/run-stage" --scene "$tmp/crate.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/c.h5" --quiet
[ -e "$tmp/c.h5" ] && { echo "FAIL output written for a checkpoint outside the box"; fail=1; }
check "box of the same name moved: warned" 0 "warning: .*a.h5: 86 of 86 particles lie outside the closed box \"box\" as .*moved.toml places it, beyond its face box.xmin .*; the run keeps the box where the checkpoint left it" -- \
  "$bin/run-stage" --scene "$tmp/moved.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/m.h5" --quiet
check "particles inside: no warning" 0 "removed 34 particles" -- "$bin/run-stage" --scene "$src/data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/s.h5" --quiet
grep -q warning "$tmp/out" && { echo "FAIL a warning for particles inside the box"; cat "$tmp/out"; fail=1; }
exit $fail
