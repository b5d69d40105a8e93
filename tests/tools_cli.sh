#!/usr/bin/env bash
# Command-line behaviour shared by the tools (the five and dem-render): --help, --version, exit codes (README), clear
# errors for bad input, and no output file left behind when a run fails.
set -u
bin=$1 data=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/check_lib.sh"  # check NAME EXPECTED_CODE PATTERN -- command...
for t in gen-primary copy-settle compact run-stage post-macro dem-render; do
  check "$t --help" 0 "--scene\|--reference\|--color-by" -- "$bin/$t" --help
  check "$t --version" 0 "^$t (dem) 0\.1\.0 (commit [0-9A-Za-z._-]*)$" -- "$bin/$t" --version
  check "$t missing required option" 2 "is required" -- "$bin/$t"
done
for t in gen-primary copy-settle compact; do
  args=(--scene "$data/small.toml" --out "$tmp/x.h5"); [ $t = gen-primary ] || args+=(--in "$data/small.toml")
  check "$t unknown option" 2 "not expected: --bogus" -- "$bin/$t" "${args[@]}" --bogus
done
check "run-stage unknown option" 2 "not expected: --bogus" -- "$bin/run-stage" --scene "$data/small.toml" --stage s --in "$data/small.toml" --out b --bogus
check "post-macro bad axis" 2 "--axis" -- "$bin/post-macro" --reference "$data/small.toml" --in "$data/small.toml" --axis w

# Scene errors: exit 3, file:line in the message, no output written.
printf '[[material]]\nname = "g"\ndensity = -1.0\nkn = 1.0\n' > "$tmp/bad.toml"
check "bad scene" 3 "bad.toml:3:11: material\[0\].density = -1: out of range" -- "$bin/gen-primary" --scene "$tmp/bad.toml" --out "$tmp/o.h5"
[ -e "$tmp/o.h5" ] && { echo "FAIL output written after a bad scene"; fail=1; }
printf '[[material]]\nname = "g"\ndensity = 1.0\nkn = 1.0\n' > "$tmp/nogen.toml"
check "no [generation]" 3 "needs a \[generation\] table" -- "$bin/gen-primary" --scene "$tmp/nogen.toml" --out "$tmp/o.h5"
check "missing scene file" 2 "File does not exist" -- "$bin/gen-primary" --scene "$tmp/none.toml" --out "$tmp/o.h5"

# Checkpoint errors: exit 4 with the reason.
"$bin/gen-primary" --scene "$data/small.toml" --out "$tmp/a.h5" --quiet > /dev/null || { echo "FAIL gen-primary"; exit 1; }
# A missing input file is a bad command line for every tool (exit 2, README "Exit codes"), before
# anything is read or written.
check "run-stage missing --in" 2 "--in: File does not exist: .*none.h5" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/none.h5" --out "$tmp/b.h5"
check "copy-settle missing --in" 2 "--in: File does not exist: .*none.h5" -- "$bin/copy-settle" --scene "$data/small.toml" --in "$tmp/none.h5" --out "$tmp/b.h5"
check "compact missing --in" 2 "--in: File does not exist: .*none.h5" -- "$bin/compact" --scene "$data/small.toml" --in "$tmp/none.h5" --out "$tmp/b.h5"
check "post-macro missing --in" 2 "--in: File does not exist: .*none.h5" -- "$bin/post-macro" --in "$tmp/none.h5" --vtk "$tmp/b.vtu"
[ -e "$tmp/b.h5" ] || [ -e "$tmp/b.vtu" ] && { echo "FAIL output written after a missing --in"; fail=1; }
# Where the file is there but is no checkpoint, it is a file error (exit 4).
echo "not hdf5" > "$tmp/text.h5"
check "text file as checkpoint" 4 "not a dem checkpoint" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/text.h5" --out "$tmp/b.h5"
head -c 20000 "$tmp/a.h5" > "$tmp/cut.h5"
check "truncated checkpoint" 4 "cut.h5" -- "$bin/post-macro" --reference "$tmp/a.h5" --in "$tmp/cut.h5" --vtk "$tmp/d.vtu"
[ -e "$tmp/d.vtu" ] && { echo "FAIL output written after a bad checkpoint"; fail=1; }
# Files found by fuzzing the checkpoint reader (each once crashed HDF5 or exhausted memory).
for f in "$data"/fuzz/*.h5; do
  check "fuzz regression $(basename "$f")" 4 "damaged" -- "$bin/post-macro" --reference "$f" --in "$f"
done
check "unknown stage" 3 'no \[\[stage\]\] named "drill" (defined: shake, long)' -- "$bin/run-stage" --scene "$data/small.toml" --stage drill --in "$tmp/a.h5" --out "$tmp/b.h5"
check "tracked id not in the model" 3 "no particle with id 99999" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5" --track "$tmp/t.csv" --track-ids 99999
[ -e "$tmp/t.csv" ] || [ -e "$tmp/t.csv.partial" ] || [ -e "$tmp/b.h5" ] && { echo "FAIL output written after a bad --track-ids"; fail=1; }
check "track ids without a file" 2 "requires --track" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5" --track-ids 3
check "negative track id" 2 "track-ids" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5" --track "$tmp/t.csv" --track-ids -1
sed 's/^frac = 0.1/frac = 0.1\ntime_step = 1.0e-3/' "$data/small.toml" > "$tmp/fast.toml"
check "time step above critical" 3 "exceeds the critical time step" -- "$bin/run-stage" --scene "$tmp/fast.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5"
sed 's/^frac = 0.1/frac = 0.1\ntime_step = 4.2e-5\nforce_time_step = true/' "$data/small.toml" > "$tmp/forced.toml"
# (a step just above eq. 2.48's limit may still blow up with many contacts: exit 0 or 5)
"$bin/run-stage" --scene "$tmp/forced.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/forced.h5" --quiet > "$tmp/out" 2>&1
rc=$?
if { [ $rc -eq 0 ] || [ $rc -eq 5 ]; } && grep -q "warning: forced time step 4.2e-05 s exceeds the critical step" "$tmp/out"; then echo "ok   forced time step warns"
else echo "FAIL forced time step warns (exit $rc)"; cat "$tmp/out"; fail=1; fi
# Unstable physics: a forced step 24x the critical one stops with a diagnosis, exit 5, no output.
sed 's/^frac = 0.1/frac = 0.1\ntime_step = 1.0e-3\nforce_time_step = true/' "$data/small.toml" > "$tmp/blowup.toml"
check "blow-up diagnosed" 5 "unstable simulation: overlap of .* between particles [0-9]* and [0-9]*, with dt = 0.001 s against the critical" -- "$bin/gen-primary" --scene "$tmp/blowup.toml" --out "$tmp/blowup.h5"
[ -e "$tmp/blowup.h5" ] && { echo "FAIL output written after a blow-up"; fail=1; }
# Energy created (simulation.max_energy_gain): a sphere dropped with twice the critical step gains
# energy at its first bounce while its overlaps stay a few % of the radius; the run stops there, writes
# no output and keeps its last periodic checkpoint (without the check it runs 40x longer, to an overlap).
"$bin/gen-primary" --scene "$data/energy_drop.toml" --out "$tmp/drop0.h5" --quiet > /dev/null 2>&1
check "energy gain diagnosed" 5 "unstable simulation: energy created at step [0-9]* .* the most energetic particle is id 0 (speed .* against the critical" -- \
  "$bin/run-stage" --scene "$data/energy_drop.toml" --stage drop --in "$tmp/drop0.h5" --out "$tmp/drop1.h5" --checkpoint-every 20 --quiet
[ -e "$tmp/drop1.h5" ] && { echo "FAIL output written after an energy gain"; fail=1; }
check "checkpoint kept after an energy gain" 0 "" -- "$bin/post-macro" --reference "$tmp/drop0.h5" --in "$tmp/drop1.restart.h5" --vtk "$tmp/drop.vtu"
# NaN/Inf: a gravity of 1e308 m/s^2 overflows the velocity (the energy sums overflow first and
# are skipped: inf - inf is no excess); the non-finite check names the step and the particle.
sed -e 's/^gravity = .*/gravity = [0.0, 0.0, -1.0e308]/' "$data/energy_drop.toml" > "$tmp/overflow.toml"
check "non-finite state diagnosed" 5 "unstable simulation: non-finite state at step [0-9]* .* for particle id 0, with dt = .*: check the time step" -- \
  "$bin/run-stage" --scene "$tmp/overflow.toml" --stage drop --in "$tmp/drop0.h5" --out "$tmp/drop3.h5" --quiet
[ -e "$tmp/drop3.h5" ] && { echo "FAIL output written after a non-finite state"; fail=1; }
# The bounce at twice the critical step stays bounded since the dashpot integrates the overlap
# (docs/contact-laws.md, "The dashpot in time"; the thesis's half-step dashpot fed it energy): a
# gravity of 1e4 m/s^2 drives the sphere into the floor instead, which the overlap check stops.
sed -e 's/^force_time_step = true/force_time_step = true\nmax_energy_gain = 0/' -e 's/^gravity = .*/gravity = [0.0, 0.0, -1.0e4]/' \
  "$data/energy_drop.toml" > "$tmp/drop_nocheck.toml"
check "energy check off: overlap stops it later" 5 "overlap of .* between particle 0 and wall floor.zmin" -- \
  "$bin/run-stage" --scene "$tmp/drop_nocheck.toml" --stage drop --in "$tmp/drop0.h5" --out "$tmp/drop2.h5" --quiet

# Implausible values (docs/scene.md, "Warnings"): a warning with the place, the value and the likely
# unit, and the run goes on (exit 0); FRAC above 0.2 gives wrong results and is refused unless forced.
# (a settle of 0.01 s: the light spheres take a step 32 times shorter, and the warning is the point)
sed 's/^density = 2500.0/density = 2.5/; s/^max_time = 0.3/max_time = 0.01/' "$data/small.toml" > "$tmp/gcm3.toml"
check "density in g/cm^3 warns and runs" 0 "gen-primary: warning: .*gcm3.toml:8:11: material\[0\].density = 2.5: density 2.5 kg/m^3, outside \[100, 25000\] kg/m^3 of granular solids: is it in g/cm^3? (kg/m^3 expected" -- \
  "$bin/gen-primary" --scene "$tmp/gcm3.toml" --out "$tmp/gcm3.h5" --quiet
sed 's/^frac = 0.1/frac = 0.9/' "$data/small.toml" > "$tmp/frac.toml"
check "frac above 0.2 refused" 3 "frac.toml:3:8: simulation.frac = 0.9: above 0.2 a contact lasts fewer than 8 steps and the results are wrong .* or set simulation.force_time_step = true" -- \
  "$bin/gen-primary" --scene "$tmp/frac.toml" --out "$tmp/frac.h5"
[ -e "$tmp/frac.h5" ] && { echo "FAIL output written after a refused frac"; fail=1; }
# Blow-ups name the likely cause, found at step 0, before the time step: a generation box wider than
# the walls (spheres placed across them) and a vibration amplitude given in mm (2 m at 20 Hz).
sed 's/^box_min = .*/box_min = [-0.01, -0.01, 0.0]/; s/^box_max = .*/box_max = [0.03, 0.03, 0.05]/' "$data/small.toml" > "$tmp/widebox.toml"
check "generation box across the walls diagnosed" 5 "unstable simulation: overlap of .* Likely causes, most likely first (checked at step 0): (1) the generation box \[-0.01, -0.01, 0\] to \[0.03, 0.03, 0.05\] m is not inside the walls: wall \"box\" (4 elements) crosses it .*(2) otherwise the time step or the stiffness: lower the time step" -- \
  "$bin/gen-primary" --scene "$tmp/widebox.toml" --out "$tmp/widebox.h5" --quiet
grep -q "gen-primary: warning: the generation box" "$tmp/out" || { echo "FAIL no warning before the run for the generation box"; fail=1; }
sed 's/^acceleration = 29.43/amplitude = 2.0/' "$data/small.toml" > "$tmp/mm.toml"
check "vibration amplitude in mm diagnosed" 5 "unstable simulation: .* Likely causes, most likely first (checked at step 0): (1) wall \"box\" moves faster than the particles can follow: peak speed 251.3.* m/s (vibration amplitude 2 m x 2 pi x 20 Hz), peak acceleration 3219.* g; it moves .* of the smallest radius .* vibration amplitude in mm? (m expected)" -- \
  "$bin/run-stage" --scene "$tmp/mm.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/mm.h5" --quiet
grep -q "run-stage: warning: wall \"box\" moves faster than the particles can follow" "$tmp/out" || { echo "FAIL no warning before the run for the fast wall"; fail=1; }
grep -q "run-stage: warning: .*stage\[0\].motion\[0\].amplitude = 2: .*amplitude in mm" "$tmp/out" || { echo "FAIL no scene warning for the amplitude"; fail=1; }
[ -e "$tmp/mm.h5" ] && { echo "FAIL output written after a blow-up"; fail=1; }
# A plausible scene runs without a warning.
"$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/ok.h5" --quiet > "$tmp/out" 2>&1
grep -q "warning" "$tmp/out" && { echo "FAIL warnings for a plausible scene:"; cat "$tmp/out"; fail=1; } || echo "ok   no warning for a plausible scene"

# A full disk (here a file-size limit): the write fails with exit 4 and the previous output stays intact.
"$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/full.h5" --quiet 2> /dev/null
cp "$tmp/full.h5" "$tmp/full.copy.h5"
check "file size limit" 4 "full.h5" -- bash -c "ulimit -f 20; exec '$bin/run-stage' --scene '$data/small.toml' --stage shake --in '$tmp/a.h5' --out '$tmp/full.h5' --quiet"
cmp -s "$tmp/full.h5" "$tmp/full.copy.h5" || { echo "FAIL the previous output was damaged by a failed write"; fail=1; }
ls "$tmp"/*.tmp 2> /dev/null && { echo "FAIL temporary left behind"; fail=1; }
sed 's/^name = "glass"/name = "sand"/; s/glass = 1.0/sand = 1.0/' "$data/small.toml" > "$tmp/other.toml"
check "material missing from scene" 3 'material "glass", which this scene does not define' -- "$bin/run-stage" --scene "$tmp/other.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5"
[ -e "$tmp/b.h5" ] && { echo "FAIL output written after failed runs"; fail=1; }

# Unwritable outputs fail at once (exit 4, the option and the path named), before any step, and
# write nothing. (A path under a regular file: permissions do not stop root.)
echo "a file" > "$tmp/file.txt"
bad=$tmp/file.txt/sub
check "gen-primary unwritable --out" 4 "gen-primary: error: --out $bad/x.h5: cannot write there: $tmp/file.txt is a file, not a folder" -- "$bin/gen-primary" --scene "$data/small.toml" --out "$bad/x.h5"
check "copy-settle unwritable --out" 4 "--out $bad/x.h5: cannot write there" -- "$bin/copy-settle" --scene "$data/tiled.toml" --in "$tmp/a.h5" --out "$bad/x.h5"
check "run-stage --out is a folder" 4 "--out $tmp: cannot write there: it is a folder" -- "$bin/run-stage" --scene "$data/small.toml" --stage long --in "$tmp/a.h5" --out "$tmp"
for opt in --wall-forces --track; do
  extra=(); [ $opt = --track ] && extra=(--track-ids 0)
  check "run-stage unwritable $opt" 4 "$opt $bad/t.csv: cannot write there" -- "$bin/run-stage" --scene "$data/small.toml" --stage long --in "$tmp/a.h5" --out "$tmp/w.h5" $opt "$bad/t.csv" "${extra[@]}"
done
start=$(date +%s%N)
check "run-stage unwritable --vtk" 4 "run-stage: error: --vtk $bad: cannot write there: $tmp/file.txt is a file, not a folder" -- "$bin/run-stage" --scene "$data/small.toml" --stage long --in "$tmp/a.h5" --out "$tmp/w.h5" --vtk "$bad"
ms=$(( ($(date +%s%N) - start) / 1000000 ))
# (the stage takes seconds; the check comes before the checkpoint is even read)
[ $ms -lt 1500 ] || { echo "FAIL unwritable --vtk reported after $ms ms, not at once"; fail=1; }
[ -e "$tmp/w.h5" ] || [ -e "$tmp/w.restart.h5" ] || [ -e "$tmp/file.txt.partial" ] && { echo "FAIL output written after an unwritable --vtk"; fail=1; }
check "post-macro unwritable --grid" 4 "--grid $bad/g.vti: cannot write there" -- "$bin/post-macro" --in "$tmp/a.h5" --grid "$bad/g.vti" --cell 0.005 --width 0.004 --vtk "$tmp/p.vtu"
[ -e "$tmp/p.vtu" ] && { echo "FAIL post-macro wrote --vtk before failing on --grid"; fail=1; }
# A --vtk folder holding a longer earlier series of the stage: its stale frames go, other files stay.
mkdir -p "$tmp/vtk/shake"
for k in 0 1 2 3 4 5 6 7 8 9; do echo old > "$tmp/vtk/shake/particles_00000$k.vtu"; echo old > "$tmp/vtk/shake/walls_00000$k.vtp"; done
echo mine > "$tmp/vtk/shake/notes.txt"; echo mine > "$tmp/vtk/other_particles.pvd"; echo mine > "$tmp/vtk/shake/particles_final.vtu"
"$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/v.h5" --vtk "$tmp/vtk" --quiet 2> /dev/null
got=$(cd "$tmp/vtk" && find . -type f | sort | tr '\n' ' ')
want="./other_particles.pvd ./shake/notes.txt ./shake/particles_000000.vtu ./shake/particles_000001.vtu ./shake/particles_000002.vtu ./shake/particles_000003.vtu ./shake/particles_final.vtu ./shake/walls_000000.vtp ./shake/walls_000001.vtp ./shake/walls_000002.vtp ./shake/walls_000003.vtp ./shake_particles.pvd ./shake_walls.pvd "
[ "$got" = "$want" ] && ! grep -q old "$tmp/vtk/shake/particles_000003.vtu" && echo "ok   stale frames of a longer run removed, other files kept" || { echo "FAIL stale frames: got $got"; fail=1; }
# A run that fails writes no frames (here it blows up at its first bounce).
"$bin/run-stage" --scene "$data/energy_drop.toml" --stage drop --in "$tmp/drop0.h5" --out "$tmp/drop4.h5" --vtk "$tmp/vtk_fail" --quiet > /dev/null 2>&1
left=$(find "$tmp/vtk_fail" -type f 2> /dev/null)
[ -z "$left" ] && echo "ok   a failed run leaves no frames" || { echo "FAIL a failed run left frames: $left"; fail=1; }
check "threads option" 0 "removed" -- "$bin/run-stage" --scene "$data/small.toml" --stage shake --in "$tmp/a.h5" --out "$tmp/b.h5" --threads 1 --quiet
exit $fail
