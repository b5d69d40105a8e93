#!/usr/bin/env bash
# The fibre-soil case's scene variants (workflows/fibre-soil/scene_variant.sh), which the case's
# make targets run but the suite's small test uses only one of: each variant edits exactly what it
# names and gives a scene the tools accept (gen-primary reads the whole scene, stages included);
# a scene the script does not know, or an unknown variant, stops it with exit 3 and no output.
set -euo pipefail
bin=$1 src=$(cd "$2" && pwd)
case_dir=$src/../workflows/fibre-soil
variant=$case_dir/scene_variant.sh scene=$case_dir/scene.toml
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# changed VARIANTS: the lines the variants change, as "> line" (diff's), sorted
changed() { bash "$variant" "$scene" "$@" > "$tmp/v.toml" && diff "$scene" "$tmp/v.toml" | grep '^>' | sort | uniq -c | sed 's/^ *//'; }
[ "$(changed dense)" = "1 > friction_angle = 0.0" ] || fail "dense: $(changed dense)"
# the soil's friction, not the platen's
awk '/^name = "soil"$/{m=1} m && /^friction_angle/{print; exit}' "$tmp/v.toml" | grep -q '= 0.0$' || fail "dense: not the soil's friction"
"$bin/gen-primary" --scene "$tmp/v.toml" --out "$tmp/dense.h5" --quiet > /dev/null || fail "dense: scene refused"
expected_half='3 > duration = 0.3
3 > output_every = 0.03
3 > velocity = [0.0, 0.0, -0.0075]
3 > velocity = [0.0, 0.0, 0.0075]'
[ "$(changed half)" = "$expected_half" ] || fail "half: $(changed half)"
"$bin/gen-primary" --scene "$tmp/v.toml" --out "$tmp/half.h5" --quiet > /dev/null || fail "half: scene refused"
[ "$(changed seed=12)" = "1 > seed = 12" ] || fail "seed=12: $(changed seed=12)"
"$bin/gen-primary" --scene "$tmp/v.toml" --out "$tmp/seed.h5" --quiet > /dev/null || fail "seed=12: scene refused"
[ -z "$(changed seed=11)" ] || fail "seed=11 (the scene's own) changed lines"
# A scene the script does not know, and an unknown variant.
sed 's/^count = 2000$/count = 2001/' "$scene" > "$tmp/other.toml"
set +e
bash "$variant" "$tmp/other.toml" small > "$tmp/out.toml" 2> "$tmp/err"; rc=$?
bash "$variant" "$scene" denser > "$tmp/out2.toml" 2> "$tmp/err2"; rc2=$?
set -e
[ $rc = 3 ] && [ ! -s "$tmp/out.toml" ] && grep -q "not the fibre-soil scene" "$tmp/err" || fail "a foreign scene: exit $rc, $(cat "$tmp/err")"
[ $rc2 = 3 ] && [ ! -s "$tmp/out2.toml" ] && grep -q "unknown variant 'denser'" "$tmp/err2" || fail "an unknown variant: exit $rc2"
echo "fibre_soil_variants: ok"
