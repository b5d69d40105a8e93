#!/usr/bin/env bash
# Tiled models are homogeneous (SPEC §9, issue "Model generation"): 600 spheres settled in a
# 30 x 30 mm box, copied 2 x 2 into a 60 x 60 mm box and settled again. Solid fraction (post-macro
# --average-csv: sphere volumes by centre over each box) of the bottom 20 mm of the bed (the
# surface is at ~29 mm):
#  - each tile within 0.02 of the tiles' mean (measured: 0.546-0.562, mean 0.555). Why 0.02:
#    counting ~400 spheres by centre in a 30 x 30 x 20 mm box moves the fraction by ~0.014 for
#    +-10 spheres on its faces;
#  - the 30 x 30 mm box centred on the four seams is no looser than the tiles less 0.02
#    (measured 0.572, denser than the tiles, which touch two walls each): gaps left at the seams
#    would show here first;
#  - no overlap deeper than 1 % of the smaller radius anywhere (the seams are where copies meet).
set -eu
bin=$1 src=$2 py=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin/gen-primary" --scene "$src/data/tile_primary.toml" --out "$tmp/primary.h5" --quiet
"$bin/copy-settle" --scene "$src/data/tile_copy.toml" --in "$tmp/primary.h5" --out "$tmp/tiled.h5" --quiet
"$bin/post-macro" --in "$tmp/tiled.h5" --average-csv "$tmp/tiles.csv" --region box:0,0,0,0.03,0.03,0.02 \
  --region box:0.03,0,0,0.06,0.03,0.02 --region box:0,0.03,0,0.03,0.06,0.02 --region box:0.03,0.03,0,0.06,0.06,0.02 \
  --region box:0.015,0.015,0,0.045,0.045,0.02 > /dev/null
"$py" - "$tmp/tiles.csv" "$tmp/tiled.h5" <<'PY'
import csv, sys
import h5py
import numpy as np
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
phi = [float(r["solid_fraction"]) for r in rows]
tiles, seams = phi[:4], phi[4]
mean = sum(tiles) / 4
print("solid fraction per tile:", " ".join(f"{p:.4f}" for p in tiles), f"mean {mean:.4f}; across the seams {seams:.4f}")
with h5py.File(sys.argv[2], "r") as f:
    x, r = f["particles/position"][()], f["particles/radius"][()]
worst = -np.inf  # deepest overlap / smaller radius, all pairs (brute force in blocks of rows)
for a in range(0, len(x), 200):
    d = np.linalg.norm(x[a:a + 200, None, :] - x[None, :, :], axis=2)
    u = (r[a:a + 200, None] + r[None, :] - d) / np.minimum(r[a:a + 200, None], r[None, :])
    u[np.arange(len(u)), np.arange(a, a + len(u))] = -np.inf  # a sphere with itself
    worst = max(worst, u.max())
print(f"{len(x)} spheres, deepest overlap {worst:.4%} of the smaller radius")
checks = [
    ("every tile within 0.02 of the mean", max(abs(p - mean) for p in tiles) <= 0.02),
    ("the seams are no looser than the tiles", seams >= mean - 0.02),
    ("no overlap beyond 1 % of the radius", worst < 0.01),
    ("all 2,400 spheres", len(x) == 2400),
]
for name, ok in checks:
    print(("ok   " if ok else "FAIL ") + name)
sys.exit(0 if all(ok for _, ok in checks) else 1)
PY
