#!/usr/bin/env bash
# post-macro on a 1,000,000-particle checkpoint (bench/post_bench.cpp builds it: a lattice of 1 mm
# spheres, 3e6 contacts, 6 walls, and a reference state for displacements), with 1 and 2 threads;
# writes bench/results/post.md. Usage: bash bench/run_post_bench.sh [N]   (from the repository
# root; about 3 minutes on 2 cores, 1.5 GB of memory and 1 GB of disk in a temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-1000000}
make -f Makefile.cases build > /dev/null
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
build/bench/post_bench "$n" "$tmp" > /dev/null
pm=build/tools/post-macro
declare -A cases
cases[stress]="--in $tmp/post_cur.h5 --average-csv $tmp/a.csv --stress-csv $tmp/s.csv"
cases[all]="--reference $tmp/post_ref.h5 --in $tmp/post_cur.h5 --vtk $tmp/p.vtu --chains $tmp/c.vtp --grid $tmp/g.vti --cell 0.004 --width 0.002 --average-csv $tmp/a.csv --stress-csv $tmp/s.csv --csv $tmp/d.csv"
cases[grid]="--reference $tmp/post_ref.h5 --in $tmp/post_cur.h5 --grid $tmp/g.vti --cell 0.002 --width 0.002"
declare -A what
what[stress]="stress tables only (box average, profile)"
what[all]="every output: particles .vtu, chains .vtp, grid .vti (cell 4 mm, w 2 mm), tables"
what[grid]="grid only, fine: cell 2 mm, w 2 mm, with displacement fields"
out=bench/results/post.md
$pm --in "$tmp/post_cur.h5" > "$tmp/log"
counts=$(sed -n 's/^post-macro: \([0-9]*\) particles, \([0-9]*\) particle contacts, \([0-9]*\) wall contacts.*/\1 spheres, \2 particle contacts and \3 wall contacts/p' "$tmp/log")
size=$(( $(stat -c %s "$tmp/post_cur.h5") / 1000000 ))
{
  echo "# post-macro on a $(echo "$n" | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta')-particle checkpoint"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), a VM shared"
  echo "with other work), dem $($pm --version | awk '{print $NF}'), g++ -O2. Reproduce: \`bash bench/run_post_bench.sh\`."
  echo
  echo "The checkpoint (bench/post_bench.cpp): spheres of radius 1 mm on a simple cubic lattice, every"
  echo "neighbour pair overlapping: $counts; $size MB. The reference checkpoint lacks every 10th"
  echo "particle. Times are post-macro's own phases (seconds, one run each); memory is the peak resident"
  echo "set (\`/usr/bin/time\`)."
  echo
  echo "| outputs | grid nodes | threads | reading | contact forces | particle stress | grid | writing | total | peak memory |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for c in stress all grid; do
    for t in 1 2; do
      # shellcheck disable=SC2086
      /usr/bin/time -f "%M" -o "$tmp/mem" $pm --threads "$t" ${cases[$c]} > "$tmp/log"
      times=$(sed -n 's/^post-macro: times \[s\]: //p' "$tmp/log")
      r=$(echo "$times" | sed 's/.*reading \([0-9.]*\).*/\1/'); f=$(echo "$times" | sed 's/.*contact forces \([0-9.]*\).*/\1/')
      s=$(echo "$times" | sed 's/.*particle stress \([0-9.]*\).*/\1/'); g=$(echo "$times" | sed 's/.*grid \([0-9.]*\).*/\1/')
      w=$(echo "$times" | sed 's/.*writing \([0-9.]*\).*/\1/'); T=$(echo "$times" | sed 's/.*total \([0-9.]*\).*/\1/')
      nodes=$(sed -n 's/^post-macro: grid \([0-9]*\) x \([0-9]*\) x \([0-9]*\) nodes.*/\1 x \2 x \3/p' "$tmp/log")
      echo "| ${what[$c]} | ${nodes:--} | $t | $r | $f | $s | $g | $w | $T | $(( $(cat "$tmp/mem") / 1024 )) MB |"
    done
  done
  echo
  echo "Where the time goes: *contact forces* is the neighbour search and one force evaluation on a"
  echo "copy of the state (a checkpoint keeps the contact history, not the forces), dominated by memory"
  echo "traffic (copying the state, compacting the contact lists), so a second thread hardly helps;"
  echo "*grid* is the coarse-graining (each contact's force spread along its branch vector, each node"
  echo "within 3.46 w), planes of nodes dealt to threads; *writing* is mostly VTK's zlib compression,"
  echo "single-threaded. The machine is shared: single runs vary by 10-30 %."
  echo
  echo "Command lines (post_cur.h5 and post_ref.h5: \`build/bench/post_bench $n DIR\`):"
  echo
  for c in stress all grid; do echo "- ${what[$c]}: \`post-macro $(echo "${cases[$c]}" | sed "s#$tmp/##g")\`"; done
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
