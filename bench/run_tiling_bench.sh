#!/usr/bin/env bash
# Generation by tiling against settling the whole sample at once (thesis §3.3: "copies are
# cheaper"); writes bench/results/tiling.md.
# Usage: bash bench/run_tiling_bench.sh [THREADS] [SIZES]   (from the repository root)
#   default: 1 thread, SIZES="100000 1000000" (about 1.5 hours on one core of this VM); needs
#   /usr/bin/time (Debian package `time`) for the peak memory. Rows of other sizes already in
#   tiling.md are kept, and so is the text under its table.
# For each size N: (a) gen-primary places N spheres at random in the whole box and settles them;
# (b) gen-primary settles N/T spheres in one tile's footprint and copy-settle tiles it
# sqrt(T) x sqrt(T) and settles again (T = 16 for 1e5, 100 for 1e6). Glass spheres of 18-22 mm
# (kn = kt = 1e5 N/m, friction 25 deg, restitution 0.3) in a bed about ten diameters deep,
# placed at random up to twice that height; both settle to the same criterion (mean kinetic
# energy below 1e-4 m g d per particle, checked every 0.01 s, at most 3 s).
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-1} sizes=${2:-"100000 1000000"}
make -f Makefile.cases build > /dev/null
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
out=bench/results/tiling.md

# scene FILE SIDE_X SIDE_Y COUNT [COPY_N SPACING]: a box SIDE_X x SIDE_Y x 0.5 m, open at the top
scene() {
  local file=$1 sx=$2 sy=$3 count=$4 copies=${5:-} spacing=${6:-}
  cat > "$file" <<TOML
[simulation]
frac = 0.1
gravity = [0.0, 0.0, -9.81]

[[material]]
name = "glass"
density = 2500.0
kn = 1.0e5
kt = 1.0e5
friction_angle = 25.0
restitution = 0.3

[[wall]]
name = "box"
material = "glass"
type = "box"
min = [0.0, 0.0, 0.0]
max = [$sx, $sy, 0.5]
faces = ["xmin", "xmax", "ymin", "ymax", "zmin"]
TOML
  if [ -z "$copies" ]; then
    cat >> "$file" <<TOML

[generation]
box_min = [0.0, 0.0, 0.0]
box_max = [$sx, $sy, 0.45]
count = $count
radius_min = 0.009
radius_max = 0.011
seed = 3
materials = { glass = 1.0 }

[generation.settle]
ke_ratio = 1.0e-4
check_every = 0.01
max_time = 3.0
TOML
  else
    cat >> "$file" <<TOML

[copy]
nx = $copies
ny = $copies
spacing = [$spacing, $spacing, 0.5]

[copy.settle]
ke_ratio = 1.0e-4
check_every = 0.01
max_time = 3.0
TOML
  fi
}

# run LABEL COMMAND...: wall seconds and the tool's summary line
run() {
  local label=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f %M -o "$work/$label.rss" "$@" --threads "$threads" --quiet > "$work/$label.log" 2>&1
  t1=$(date +%s.%N)
  echo "$(echo "$t1 - $t0" | bc)" > "$work/$label.time"
}

rows=()
for n in $sizes; do
  case $n in 100000) tiles=4 ;; 1000000) tiles=10 ;; *) echo "size $n: use 100000 or 1000000" >&2; exit 2 ;; esac
  per=$(( n / (tiles * tiles) ))
  # One tile holds `per` spheres in a bed ~10 diameters (0.2 m) deep at solid fraction ~0.6.
  side=$(python3 -c "import math; print(round(math.sqrt($per * 4 / 3 * math.pi * 0.01**3 / (0.6 * 0.2)), 4))")
  full=$(python3 -c "print(round($side * $tiles, 4))")
  scene "$work/whole_$n.toml" "$full" "$full" "$n"
  scene "$work/primary_$n.toml" "$side" "$side" "$per"
  scene "$work/copy_$n.toml" "$full" "$full" 0 "$tiles" "$side"
  run "whole_$n" build/tools/gen-primary --scene "$work/whole_$n.toml" --out "$work/whole_$n.h5"
  run "primary_$n" build/tools/gen-primary --scene "$work/primary_$n.toml" --out "$work/primary_$n.h5"
  run "copy_$n" build/tools/copy-settle --scene "$work/copy_$n.toml" --in "$work/primary_$n.h5" --out "$work/copy_$n.h5"
  summary() { sed -n 's/.*: \([0-9]*\) particles, \([0-9]*\) steps .*settled: \([a-z]*\).*porosity \([0-9.]*\), coordination \([0-9.]*\).*/\1 | \2 | \3 | \4 | \5/p' "$work/$1.log"; }
  tw=$(cat "$work/whole_$n.time") tp=$(cat "$work/primary_$n.time") tc=$(cat "$work/copy_$n.time")
  when="$threads, $(date -u +%Y-%m-%d)"
  mib() { echo $(( $(cat "$work/$1.rss") / 1024 )); }
  rows+=("| $n | whole box ${full} m square | $(summary whole_$n) | $(printf %.1f "$tw") | $when | $(mib whole_$n) |")
  rows+=("| $n | primary, one tile ${side} m square | $(summary primary_$n) | $(printf %.1f "$tp") | $when | $(mib primary_$n) |")
  rows+=("| $n | copy-settle ${tiles} x ${tiles} | $(summary copy_$n) | $(printf %.1f "$tc") | $when | $(mib copy_$n) |")
  rows+=("| $n | **tiling total / whole** | | | | | | $(printf %.1f "$(echo "$tp + $tc" | bc)") s / $(printf %.1f "$tw") s = **$(python3 -c "print(f'{($tp + $tc) / $tw:.2f}')")** | $when | |")
done
# Rows of sizes not measured now, and the notes under the table, are kept from the previous file.
kept_rows=$(awk -F'|' -v sizes=" $sizes " 'NR > 1 && /^\| [0-9]/ && index(sizes, " " ($2 + 0) " ") == 0' "$out" 2> /dev/null || true)
notes=$(awk 'table && !/^\|/ {rest = 1} rest {print} /^\|---/ {table = 1}' "$out" 2> /dev/null || true)
{
  echo "# Generation: tiling against settling the whole sample"
  echo
  echo "Machine: $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), dem $(build/tools/run-stage --version | awk '{print $NF}')."
  echo "Reproduce: \`bash bench/run_tiling_bench.sh THREADS N\` (the row's threads and N)."
  echo "Scene and method: the comment at the top of bench/run_tiling_bench.sh. Porosity is over the"
  echo "container up to the highest sphere top (the rough surface counts as void), coordination per sphere;"
  echo "peak RSS of the tool's process."
  echo
  echo "| N | step | particles | steps | settled | porosity | coordination | wall time [s] | threads, date | peak RSS [MiB] |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  { [ -n "$kept_rows" ] && echo "$kept_rows"; printf '%s\n' "${rows[@]}"; } | sort -t'|' -k2,2n -s
  [ -n "$notes" ] && echo "$notes"
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
