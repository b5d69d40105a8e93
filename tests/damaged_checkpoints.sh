#!/usr/bin/env bash
# Writes real checkpoints (a settled box with contacts, then the box shaken by vibrating walls) and
# runs the damaged-file suite on them (tests/damaged_checkpoints.py).
set -eu
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin/gen-primary" --scene "$src/data/small.toml" --out "$tmp/settled.h5" --quiet > /dev/null
"$bin/run-stage" --scene "$src/data/small.toml" --stage shake --in "$tmp/settled.h5" --out "$tmp/good.h5" --quiet 2> /dev/null
"$py" "$src/damaged_checkpoints.py" "$bin" "$tmp/good.h5" "$tmp/work" "$tmp/settled.h5"
