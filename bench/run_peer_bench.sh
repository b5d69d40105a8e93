#!/usr/bin/env bash
# Our code beside LAMMPS and LIGGGHTS (Debian packages) on the settle scenes (10^4 and 10^5 spheres
# falling into a box) and the chute scene (32,000 spheres flowing down a periodic chute), in one
# session on one machine: every configuration REPS times, interleaved, 1 and 2 threads/processes.
# Writes bench/results/peers_runs.csv (every run) and bench/results/peers.md (medians and ratios).
# Usage: bash bench/run_peer_bench.sh [REPS] [SCENES] [MODELS]   (from anywhere; about 40 minutes on
#   2 cores with REPS=3; SCENES, default "settle:10000:20000 settle:100000:2500 chute:32000:6000",
#   each SCENE:PARTICLES:STEPS; runs of other scenes already in the runs file are kept)
# MODELS: "linear" (default: the scenes' linear spring-dashpot, inputs bench/peers/in.SCENE.CODE) or
#   any of "hertz hertz-rolling" (Hertz-Mindlin, alone or with EPSD2 / sds rolling resistance:
#   bench/hertz_models.hpp, inputs bench/peers/in.SCENE_hertz.CODE -var rolling 0|1), written to
#   bench/results/peers_hertz_runs.csv and peers_hertz.md instead; "hertz-explicit" and
#   "hertz-rolling-explicit" run ours alone with the explicit dashpot (docs/contact-laws.md eq. D7,
#   the peers' form), compared with the peers' runs of the model without the suffix, e.g.
#   bash bench/run_peer_bench.sh 3 "settle:10000:20000 chute:32000:2000" "hertz hertz-rolling hertz-explicit hertz-rolling-explicit"
# One process or thread runs pinned to CPU $PIN_CPU (default 0) for every code: on a VM whose
#   cores differ (bench/results/peers_hertz.md, "The machine's two cores"), a run left to the scheduler
#   lands on either and its time says which as much as which code it was.
# Needs: apt-get install lammps liggghts openmpi-bin time (done here when run as root).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
reps=${1:-3}
scenes=${2:-"settle:10000:20000 settle:100000:2500 chute:32000:6000"}
models=${3:-linear}
pin=${PIN_CPU:-0}
out=peers; [ "$models" = linear ] || out=peers_hertz
make -f Makefile.cases build > /dev/null
cmake --build build --target settle_bench chute_bench -- --no-print-directory > /dev/null
missing=""
for c in lmp:lammps liggghts:liggghts mpirun:openmpi-bin /usr/bin/time:time; do command -v "${c%%:*}" > /dev/null || missing="$missing ${c#*:}"; done
if [ -n "$missing" ]; then
  if [ "$(id -u)" = 0 ]; then DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $missing > /dev/null
  else echo "missing reference codes; run: sudo apt-get install -y$missing" >&2; exit 1; fi
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp bench/peers/in.settle* bench/peers/in.chute* "$work/"
csv=bench/results/${out}_runs.csv
mkdir -p bench/results
echo "scene,code,procs,particles,steps,loop_s,psps,peak_rss_kb,rep,date,model" > "$csv.tmp"
today=$(date -u +%Y-%m-%d)

# One run: prints "loop_seconds peak_rss_kb" (peak RSS of the largest process).
run_one() {  # code procs scene N steps model
  local code=$1 np=$2 scene=$3 n=$4 steps=$5 model=$6 log="$work/log" t="$work/time"
  local on=(); [ "$np" = 1 ] && on=(taskset -c "$pin")  # one process: every code on the same core
  case $code in
    dem) local bench=("$root/build/bench/settle_bench" run "$n"); [ "$scene" = chute ] && bench=("$root/build/bench/chute_bench" run)
         OMP_NUM_THREADS=$np /usr/bin/time -v -o "$t" "${on[@]}" "${bench[@]}" "$steps" "$np" "$model" > "$log"
         awk '{for (i = 1; i < NF; i++) if ($i == "loop_s") print $(i + 1)}' "$log" | tr '\n' ' ' ;;
    lammps|liggghts)
         local exe=lmp; [ "$code" = liggghts ] && exe=liggghts
         local launch=(); [ "$np" -gt 1 ] && launch=(mpirun -np "$np" --bind-to none)
         local input=("in.$scene.$code"); [ "$model" = linear ] || input=("in.${scene}_hertz.$code" -var rolling "$([ "$model" = hertz-rolling ] && echo 1 || echo 0)")
         (cd "$work" && /usr/bin/time -v -o "$t" "${on[@]}" "${launch[@]}" "$exe" -in "${input[@]}" -var N "$n" -var nsteps "$steps" -log none > "$log" 2>&1)
         awk '/^Loop time of/ {print $4}' "$log" | tr '\n' ' ' ;;
  esac
  awk -F: '/Maximum resident set size/ {gsub(/ /, "", $2); print $2}' "$t"
}

for spec in $scenes; do
  IFS=: read -r scene n steps <<< "$spec"
  case $scene in
    settle) "$root/build/bench/settle_bench" lammps-data "$n" "$work/data.settle.$n" ;;
    chute) [ "$n" = 32000 ] || { echo "chute: the scene has 32000 particles" >&2; exit 2; }
           "$root/build/bench/chute_bench" lammps-data "$work/data.chute" ;;
    *) echo "unknown scene $scene (settle or chute)" >&2; exit 2 ;;
  esac
  label="$scene $n"; [ "$scene" = chute ] && label=chute
  for rep in $(seq 1 "$reps"); do
    for np in 1 2; do
      for model in $models; do
        for code in dem lammps liggghts; do
          [ "$code" != dem ] && [[ $model == *-explicit ]] && continue  # the peers' dashpot is explicit already
          read -r loop rss < <(run_one "$code" "$np" "$scene" "$n" "$steps" "$model")
          psps=$(awk -v n="$n" -v s="$steps" -v t="$loop" 'BEGIN {printf "%.4g", n * s / t}')
          echo "$label,$code,$np,$n,$steps,$loop,$psps,$rss,$rep,$today,$model" | tee -a "$csv.tmp"
        done
      done
    done
  done
done
# Runs of scenes not measured now are kept from the previous file, with their date (peers.md shows
# it per scene: compare codes within one scene's session only).
measured=$(tail -n +2 "$csv.tmp" | cut -d, -f1 | sort -u)
if [ -f "$csv" ]; then
  tail -n +2 "$csv" | while IFS= read -r row; do
    grep -qxF "${row%%,*}" <<< "$measured" || echo "$row"
  done >> "$csv.tmp"
fi
mv "$csv.tmp" "$csv"
/usr/bin/python3 bench/summarize_peers.py "$csv" > "bench/results/$out.md.tmp"
# A hand-written analysis at the end of the file (from "## Where our time goes" on) is kept.
[ -f "bench/results/$out.md" ] && sed -n '/^## Where our time goes/,$p' "bench/results/$out.md" >> "bench/results/$out.md.tmp"
mv "bench/results/$out.md.tmp" "bench/results/$out.md"
cat "bench/results/$out.md"
