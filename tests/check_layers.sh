#!/usr/bin/env bash
# The layers of lib/ (the table is also at the top of lib/CMakeLists.txt): a file may include
# headers of its own folder or of a lower rank only; folders of equal rank are peers and include
# none of each other. Fails on an include of a higher rank or of a peer, and on a folder of lib/
# that the table does not place. Usage: check_layers.sh [LIB_DIR]
set -eu
lib=${1:-$(dirname "$0")/../lib}
rank="core=0 simd=1 contact=2 state=3 walls=4 search=5 integrate=5 forces=6 sim=7 scene=8
      generation=9 post=9 control=9 io=10 run=11"

status=0
for d in "$lib"/*/; do
  d=$(basename "$d")
  [[ " $(echo $rank) " == *" $d="* ]] || { echo "lib/$d/: folder not in the layer table of $0"; status=1; }
done

cd "$lib"
find . -name '*.hpp' -o -name '*.cpp' | sed 's#^\./##' | sort | xargs grep -Hn '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"/]*/' |
  awk -v table="$rank" '
    BEGIN { n = split(table, t, /[[:space:]]+/); for (i = 1; i <= n; i++) if (split(t[i], kv, "=") == 2) r[kv[1]] = kv[2] }
    {
      split($0, f, ":"); from = f[1]; sub(/\/.*/, "", from)
      to = $0; sub(/^[^"]*"/, "", to); sub(/\/.*/, "", to)
      if (!(from in r) || !(to in r) || from == to) next
      if (r[to] > r[from]) why = "a higher layer"; else if (r[to] == r[from]) why = "a peer"; else next
      printf "lib/%s:%s: %s (layer %d) includes %s (layer %d), %s\n", f[1], f[2], from, r[from], to, r[to], why
      bad = 1
    }
    END { exit bad }' || status=1

[ "$status" = 0 ] && echo "layers ok"
exit $status
