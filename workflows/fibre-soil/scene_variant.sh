#!/usr/bin/env bash
# Variants of the fibre-soil case's scene (workflows/fibre-soil/README.md), each an edit of its
# text; every edit must change exactly the lines it expects, else exit 3 (the scene is not the one
# this script knows), so the case and the tests never run a scene edited by half.
#   small   400 spheres filled into a 24 mm box (an 18 mm sample once pressed), sheared to 10 %
#           axial strain (0.06 s at the platen speed): tests/fibre_soil_small.sh
#   half    the platens at half their speed for twice as long (the same strains): the rate check
#   dense   the spheres frictionless: a consolidation with it packs densely; the sample is then
#           sheared with the scene itself (friction 30 deg), as a dense sand is prepared
#   seed=N  the fill drawn with seed N instead of 11: another packing, the same everything else
#   usage: scene_variant.sh SCENE.toml [small] [half] [dense] [seed=N] > VARIANT.toml
set -euo pipefail
scene=$1
shift
text=$(cat "$scene")
fail() { echo "scene_variant.sh: $scene: $*" >&2; exit 3; }
# edit SED-SCRIPT LINES: the script must change exactly LINES lines of the scene's text.
edit() {
  local new changed
  new=$(sed "$1" <<< "$text")
  changed=$(diff <(printf '%s\n' "$text") <(printf '%s\n' "$new") | grep -c '^>' || true)
  [ "$changed" = "$2" ] || fail "'$1' changed $changed lines, not $2: not the fibre-soil scene this script edits"
  text=$new
}
small=0 half=0
for v in "$@"; do
  case $v in
    small) small=1 ;;
    half) half=1 ;;
    dense) edit '/^name = "soil"$/,/^friction_angle = /s/^friction_angle = 30\.0$/friction_angle = 0.0/' 1 ;;
    seed=*)
      n=${v#seed=}
      [[ $n =~ ^[0-9]+$ ]] || fail "seed=$n: a non-negative integer is allowed"
      [ "$n" = 11 ] || edit "s/^seed = 11\$/seed = $n/" 1 ;;
    *) fail "unknown variant '$v' (allowed: small, half, dense, seed=N)" ;;
  esac
done
# The three shear stages' durations and frame intervals, and their six platen speeds.
duration=0.15 every=0.015
if [ $small = 1 ]; then
  edit 's/^count = 2000$/count = 400/' 1
  edit 's/0\.040, 0\.040, 0\.040\]/0.024, 0.024, 0.024]/' 2
  duration=0.06 every=0.006
fi
if [ $half = 1 ]; then
  edit 's/velocity = \[0\.0, 0\.0, \(-\?\)0\.015\]/velocity = [0.0, 0.0, \10.0075]/' 6
  duration=$(awk "BEGIN { print 2 * $duration }") every=$(awk "BEGIN { print 2 * $every }")
fi
[ $duration = 0.15 ] || edit "s/^duration = 0\\.15\$/duration = $duration/" 3
[ $every = 0.015 ] || edit "s/^output_every = 0\\.015\$/output_every = $every/" 3
printf '%s\n' "$text"
