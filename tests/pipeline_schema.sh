#!/usr/bin/env bash
# The tool chain end to end on a small scene: gen-primary -> run-stage (with VTK) -> post-macro;
# then the checkpoints are checked with h5py against the documented schema, and the outputs exist.
set -eu
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scene=$src/data/small.toml
"$bin/gen-primary" --scene "$scene" --out "$tmp/settled.h5" --quiet
"$bin/run-stage" --scene "$scene" --stage shake --in "$tmp/settled.h5" --out "$tmp/shaken.h5" --vtk "$tmp/vtk" --quiet
"$bin/post-macro" --reference "$tmp/settled.h5" --in "$tmp/shaken.h5" --vtk "$tmp/disp.vtu" --csv "$tmp/profile.csv" --bins 5
"$py" "$src/check_checkpoint_schema.py" "$tmp/settled.h5" gen-primary
"$py" "$src/check_checkpoint_schema.py" "$tmp/shaken.h5" run-stage
"$py" "$src/check_vtk_output.py" "$tmp/vtk" shake "$tmp/shaken.h5" "$tmp/settled.h5" "$tmp/disp.vtu"
# 0.03 s at 0.01 s cadence: frames at t0, +0.01, +0.02, end (+0.03 within one step) -> 4 frames.
frames=$(ls "$tmp/vtk/shake"/particles_*.vtu | wc -l)
[ "$frames" -eq 4 ] || { echo "expected 4 particle frames, got $frames"; exit 1; }
[ "$(grep -c '<DataSet' "$tmp/vtk/shake_particles.pvd")" -eq 4 ]
[ "$(grep -c '<DataSet' "$tmp/vtk/shake_walls.pvd")" -eq 4 ]
[ -s "$tmp/disp.vtu" ] && [ "$(grep -vc '^#' "$tmp/profile.csv")" -eq 6 ]
# The remove action took the top layer away: post-macro reports removed particles.
"$bin/post-macro" --reference "$tmp/settled.h5" --in "$tmp/shaken.h5" | grep -q -E "matched by id, [1-9][0-9]* removed since the reference"
# Tiling and compaction: twice the particles with unique ids, lid stress reported.
"$bin/copy-settle" --scene "$src/data/tiled.toml" --in "$tmp/settled.h5" --out "$tmp/tiled.h5" --quiet
"$bin/compact" --scene "$src/data/tiled.toml" --in "$tmp/tiled.h5" --out "$tmp/compacted.h5" --quiet | tee "$tmp/compact.log"
# The servo holds the lid within 2 % of the 500 Pa target.
awk '/moving-wall stress/ { s = $4; exit (s < 490 || s > 510) }' "$tmp/compact.log"
"$py" "$src/check_checkpoint_schema.py" "$tmp/tiled.h5" copy-settle | grep -q "240 particles"
"$py" "$src/check_checkpoint_schema.py" "$tmp/compacted.h5" compact | grep -q "240 particles"
ls "$tmp"/*.tmp 2>/dev/null && { echo "temporary files left behind"; exit 1; }
echo "pipeline ok"
