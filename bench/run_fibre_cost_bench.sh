#!/usr/bin/env bash
# What fibres at 1 % by volume add to a step (issue 34: at most 10 %): the fibre-soil case's 1 %
# loose sample at the end of its shear (out/fibre-soil/loose/shear_1.h5, from `make -f Makefile.cases
# fibre-soil`), sheared on for 0.002 s by run-stage on one thread under valgrind's callgrind, as it
# is (2,000 spheres, the 1 % fibres) and with its /fibres group deleted (the same spheres, contacts
# and walls, no fibres). The cost per step is the instructions inside Simulation::advance
# (inclusive: search, contacts, walls, fibres, integration) over the steps run; the fibres' own
# share is add_fibre_forces + rotate_ties inside it. Instruction counts, not times: the machine is
# shared. Prints a Markdown table for bench/results/fibres.md.
# Usage: bash bench/run_fibre_cost_bench.sh [OUT_DIR]   (about 2 minutes on one core)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-out/fibre-soil/loose}
[ -x build/tools/run-stage ] || { echo "build first: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2"; exit 1; }
[ -e "$dir/shear_1.h5" ] || { echo "run the case first: make -f Makefile.cases fibre-soil"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# Stage shear_0 (no [stage.fibres]: nothing placed again) for 0.002 s.
sed 's/^duration = 0\.15$/duration = 0.002/' workflows/fibre-soil/scene.toml > "$tmp/scene.toml"
grep -q '^duration = 0\.002$' "$tmp/scene.toml" || { echo "the scene's shear duration was not found"; exit 1; }
cp "$dir/shear_1.h5" "$tmp/with.h5"
cp "$dir/shear_1.h5" "$tmp/without.h5"
/usr/bin/python3 - "$tmp/without.h5" tests <<'PY'
import sys, h5py
sys.path.insert(0, sys.argv[2])
from damaged_checkpoints import reseal
with h5py.File(sys.argv[1], "r+") as f:
    del f["fibres"]
reseal(sys.argv[1])
PY
measure() {  # label -> "advance_Ir fibre_Ir steps segments"
  local out=$tmp/$1
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out.cg" build/tools/run-stage --scene "$tmp/scene.toml" --stage shear_0 \
    --in "$tmp/$1.h5" --out "$out.out.h5" --checkpoint-minutes 0 --quiet 2> /dev/null
  callgrind_annotate --inclusive=yes --threshold=100 "$out.cg" > "$out.txt"
  local advance fibre rotate steps segments
  advance=$(grep "dem::Simulation::advance()" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}')
  fibre=$(grep "dem::add_fibre_forces" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}')
  rotate=$(grep "dem::rotate_ties" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}')
  read -r steps segments < <(/usr/bin/python3 -c "
import sys, h5py
a, b = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
n = len(b['fibres/segment_rest_length']) if 'fibres' in b else 0
print(int(b['/state/step'][()].item()) - int(a['/state/step'][()].item()), n)" "$tmp/$1.h5" "$out.out.h5")
  echo "${advance:-0} $((${fibre:-0} + ${rotate:-0})) $steps $segments"
}
read -r a_with f_with s_with n_with <<< "$(measure with)"
read -r a_without f_without s_without n_without <<< "$(measure without)"
awk -v aw="$a_with" -v fw="$f_with" -v sw="$s_with" -v nw="$n_with" -v ao="$a_without" -v so="$s_without" 'BEGIN {
  pw = aw / sw; po = ao / so
  printf "| sample | steps | instructions per step (advance) | fibres (add_fibre_forces + rotate_ties) per step |\n|---|---|---|---|\n"
  printf "| 2,000 spheres, no fibres | %d | %.4g | 0 |\n", so, po
  printf "| the same with the 1 %% fibres (%d segments) | %d | %.4g | %.4g (%.1f instructions per segment) |\n", nw, sw, pw, fw / sw, fw / sw / nw
  printf "\nfibres at 1 %%: %+.2f %% instructions per step\n", 100 * (pw / po - 1)
}'
