#!/usr/bin/env bash
# Cost per particle-step and peak memory per particle against the number of particles (issue 5:
# it must stay flat from 10^4 to 10^6, O(N)): the chute scene (bench/chute_scene.hpp, dense and
# flowing, periodic in x and y) on wider and wider chutes of the same depth, so that every size
# runs the same physics per particle. Writes bench/results/scaling.md (and scaling_runs.csv).
# SCENE=lattice instead runs spheres pressed together on a periodic lattice (bench/lattice_scene.hpp:
# 6 contacts per sphere at every N, so the cost shows the code's own growth) and writes
# bench/results/scaling_lattice.md (and scaling_lattice_runs.csv).
# Usage: bash bench/run_scaling_bench.sh [REPS] [STEPS] [SIZES] [THREADS]   (from anywhere; default
#   2 reps of 2,000 steps, sizes "10000 32000 100000 320000 1000000", threads "1 2": about
#   15 minutes on 2 cores; needs the machine to itself for meaningful times). BUILD=dir builds and
#   runs in another build directory (as Makefile.cases), e.g. while a long run uses build/.
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-2} steps=${2:-2000} sizes=${3:-"10000 32000 100000 320000 1000000"} threads=${4:-"1 2"}
build=${BUILD:-build}
scene=${SCENE:-scaled}
case "$scene" in
  scaled) out=bench/results/scaling ;;
  lattice) out=bench/results/scaling_lattice ;;
  *) echo "run_scaling_bench.sh: SCENE must be scaled or lattice, not '$scene'" >&2; exit 2 ;;
esac
make -f Makefile.cases build BUILD="$build" > /dev/null
cmake --build "$build" --target chute_bench -- --no-print-directory > /dev/null
csv=${out}_runs.csv
echo "particles,threads,steps,loop_s,ns_per_particle_step,contacts,peak_rss_kb,rss_increase_kb,rep" > "$csv.tmp"
field() { awk -v k="$1" '{for (i = 1; i < NF; i++) if ($i == k) print $(i + 1)}'; }
for rep in $(seq 1 "$reps"); do
  for n in $sizes; do
    for t in $threads; do
      line=$(OMP_NUM_THREADS=$t "$build"/bench/chute_bench "$scene" "$n" "$steps" "$t")
      np=$(field particles <<< "$line") loop=$(field loop_s <<< "$line")
      echo "$np,$t,$steps,$loop,$(awk -v l="$loop" -v n="$np" -v s="$steps" 'BEGIN {printf "%.2f", l / n / s * 1e9}'),$(field contacts <<< "$line"),$(field rss_kb <<< "$line"),$(field rss_increase_kb <<< "$line"),$rep" >> "$csv.tmp"
      echo "rep $rep: $line" >&2
    done
  done
done
mv "$csv.tmp" "$csv"
/usr/bin/python3 - "$csv" "$steps" "$scene" > "$out.md.tmp" <<'PY'
import csv, statistics, sys, datetime, platform, subprocess
rows = list(csv.DictReader(open(sys.argv[1])))
steps = sys.argv[2]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
scene = sys.argv[3]
title = "chute scene, wider chutes" if scene == "scaled" else "spheres pressed together on a periodic lattice"
print(f"# Cost per particle-step against the number of particles ({title})\n")
print(f"Measured {datetime.date.today()} on {subprocess.run(['nproc'], capture_output=True, text=True).stdout.strip()} cores ({cpu}), "
      f"g++ -O3, OpenMP threads. Reproduce: `{'' if scene == 'scaled' else 'SCENE=lattice '}bash bench/run_scaling_bench.sh` (every run in "
      f"`{sys.argv[1]}`).\n")
if scene == "scaled":
    print(f"Scene: bench/chute_scene.hpp (the physics of LAMMPS's chute benchmark: a touching lattice 39 layers deep on a "
          f"frozen rough base collapses and flows down a periodic chute), its footprint widened to hold N spheres "
          f"(`chute_bench scaled N {steps} THREADS`); {steps} steps from the same start. The wider chutes hold "
          f"more contacts per sphere at the end (see the table), so part of the growth of the cost is the scene's.")
else:
    print(f"Scene: bench/lattice_scene.hpp (`chute_bench lattice N {steps} THREADS`): spheres of the chute's material "
          f"on a simple cubic lattice of spacing 0.99 diameters in a box periodic along all three axes, no gravity, "
          f"small random velocities: 6 contacts per sphere (3 pair contacts per particle) at every N, so the growth of "
          f"the cost is the code's own (caches, memory traffic, contacts summed per particle).")
print("Cost = loop time / (particles x steps), median of the runs; memory = peak resident set "
      "of the whole process (libraries included) and its increase over the process before the scene was built.\n")
print("| particles | threads | runs | ns per particle-step (median) | relative to the median over sizes | contacts at the end | contacts per particle | peak RSS MB | kB per particle (whole process) | kB per particle (scene only) |")
print("|---|---|---|---|---|---|---|---|---|---|")
by = {}
for r in rows:
    by.setdefault((int(r["threads"]), int(r["particles"])), []).append(r)
for t in sorted({k[0] for k in by}):
    sizes = sorted(n for (tt, n) in by if tt == t)
    cost = {n: statistics.median(float(r["ns_per_particle_step"]) for r in by[(t, n)]) for n in sizes}
    ref = statistics.median(cost.values())
    for n in sizes:
        rs = by[(t, n)]
        rss = max(int(r["peak_rss_kb"]) for r in rs)
        inc = max(int(r["rss_increase_kb"]) for r in rs)
        c = int(rs[-1]["contacts"])
        print(f"| {n:,} | {t} | {len(rs)} | {cost[n]:.1f} | {cost[n] / ref:.2f} | {c:,} | {c / n:.2f} | {rss / 1024:.0f} | "
              f"{rss * 1024 / n / 1000:.2f} | {inc * 1024 / n / 1000:.2f} |")
    spread = max(cost.values()) / min(cost.values())
    print(f"| | {t} | | largest / smallest cost: {spread:.2f} | | | | | | |")
PY
mv "$out.md.tmp" "$out.md"
cat "$out.md"
