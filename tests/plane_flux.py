#!/usr/bin/env python3
"""scripts/plane_flux.py (docs/physics.md eq. P50) against hand-counted crossings: straight paths
through, beside and along the annulus z = 1, 0.1 <= r <= 0.3 about the axis through (0.5, 0).
Every expected value is counted by hand from the geometry below; exact (counts and sums of given
masses, no tolerance needed beyond round-off of three additions)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from plane_flux import annulus_crossings  # noqa: E402

axis = (0.5, 0.0)
paths = [  # (start, end, mass): what it does
    ((0.7, 0.0, 0.9), (0.7, 0.0, 1.1), 1.0),    # up through r = 0.2: up
    ((0.7, 0.0, 1.0), (0.7, 0.0, 0.99), 2.0),   # starts on the plane (counts as above), goes down: down
    ((0.5, 0.05, 0.9), (0.5, 0.05, 1.1), 4.0),  # up at r = 0.05, inside the shaft's radius: not counted
    ((0.9, 0.0, 0.9), (0.9, 0.0, 1.1), 8.0),    # up at r = 0.4, outside the flight: not counted
    # up from r = 0.4 to r = 0.4 on the other side, passing z = 1 halfway, at (0.7, 0): r = 0.2: up
    ((0.9, 0.0, 0.9), (0.5, 0.0, 1.1), 16.0),
    # up from r = 0.25 to r = 0.05 (inside the shaft's radius), passing z = 1 at a quarter of the
    # path: at x = 0.75 - 0.05 = 0.7, r = 0.2: up
    ((0.75, 0.0, 0.95), (0.55, 0.0, 1.15), 32.0),
    ((0.7, 0.0, 0.9), (0.7, 0.0, 0.95), 64.0),  # below, stays below: not counted
    ((0.7, 0.0, 1.1), (0.7, 0.1, 1.2), 128.0),  # above, stays above: not counted
]
x0 = np.array([p[0] for p in paths])
x1 = np.array([p[1] for p in paths])
m = np.array([p[2] for p in paths])
up, down, n_up, n_down = annulus_crossings(x0, x1, m, axis, 0.1, 0.3, 1.0)
checks = [
    ("mass up %g (1 + 16 + 32 = 49)" % up, up == 49.0),
    ("mass down %g (2)" % down, down == 2.0),
    ("count up %d (3), down %d (1)" % (n_up, n_down), (n_up, n_down) == (3, 1)),
]
# Swapping the two snapshots turns every crossing round.
up2, down2, n_up2, n_down2 = annulus_crossings(x1, x0, m, axis, 0.1, 0.3, 1.0)
checks.append(("reversed: up %g, down %g (2, 49)" % (up2, down2), (up2, down2, n_up2, n_down2) == (2.0, 49.0, 1, 3)))
for name, ok in checks:
    print(("ok   " if ok else "FAIL ") + name)
sys.exit(0 if all(ok for _, ok in checks) else 1)
