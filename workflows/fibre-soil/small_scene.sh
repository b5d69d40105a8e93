#!/usr/bin/env bash
# The fibre-soil case's scene at the small size (tests/fibre_soil_small.sh and the case's rate
# check): 400 spheres filled into a 24 mm box (an 18 mm sample once pressed), sheared to 10 %
# axial strain (0.06 s at the case's platen speed, 15 mm/s each: a strain rate of about 1.7/s).
# With "half": the platens at half the speed for twice as long (the same strains).
#   usage: small_scene.sh SCENE.toml [half] > SMALL.toml
set -euo pipefail
scene=$1 rate=${2:-full}
edits=(-e 's/^count = 2000$/count = 400/' -e 's/0\.040, 0\.040, 0\.040\]/0.024, 0.024, 0.024]/'
       -e 's/^output_every = 0\.015$/output_every = 0.006/')
if [ "$rate" = half ]; then
  edits+=(-e 's/^duration = 0\.15$/duration = 0.12/' -e 's/velocity = \[0\.0, 0\.0, \(-\?\)0\.015\]/velocity = [0.0, 0.0, \10.0075]/'
          -e 's/^output_every = 0\.006$/output_every = 0.012/')
else
  edits+=(-e 's/^duration = 0\.15$/duration = 0.06/')
fi
out=$(sed "${edits[@]}" "$scene")
# Every edit must have found its line: the scene's text is what the test and the case rely on.
grep -q '^count = 400$' <<< "$out" && [ "$(grep -c '0\.024, 0\.024, 0\.024\]' <<< "$out")" = 2 ] &&
  ! grep -q '^duration = 0\.15$' <<< "$out" && ! grep -q '^output_every = 0\.015$' <<< "$out" ||
  { echo "small_scene.sh: $scene is not the fibre-soil scene this script edits" >&2; exit 3; }
if [ "$rate" = half ]; then
  ! grep -q 'velocity = \[0\.0, 0\.0, -\?0\.015\]' <<< "$out" || { echo "small_scene.sh: platen speeds not halved" >&2; exit 3; }
fi
printf '%s\n' "$out"
