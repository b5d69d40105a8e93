"""Particles crossing a horizontal annulus (a plane z = h, between radii r_in and r_out of a vertical
axis), between two snapshots of the same particles: the mass flow rate up a screw or a ramp.

Each particle's path between the snapshots is taken as straight; where it passes z = h, the point
of passage (linear interpolation of x and y) must lie within the annulus. Counted upward when it
goes from below h to h or above, downward the other way. A particle that crosses several times
between two snapshots counts once or not at all (its net crossing), so the snapshots must be close
enough for a path to be nearly straight: a rise or fall of a small fraction of the annulus's width
and a turn of a small angle about the axis between snapshots.
"""
import numpy as np


def annulus_crossings(x0, x1, mass, axis_xy, r_in, r_out, height):
    """(mass up, mass down, count up, count down) through the annulus between positions x0 and x1
    ((N, 3) arrays, row k the same particle in both) of particles of mass `mass` ((N,))."""
    z0, z1 = x0[:, 2] - height, x1[:, 2] - height
    up = (z0 < 0) & (z1 >= 0)
    down = (z0 >= 0) & (z1 < 0)
    moved = up | down
    t = np.zeros(len(z0))
    t[moved] = z0[moved] / (z0[moved] - z1[moved])   # fraction of the path at the plane
    p = x0[:, :2] + t[:, None] * (x1[:, :2] - x0[:, :2]) - np.asarray(axis_xy, dtype=float)
    r = np.hypot(p[:, 0], p[:, 1])
    inside = (r >= r_in) & (r <= r_out)
    up &= inside
    down &= inside
    return float(mass[up].sum()), float(mass[down].sum()), int(up.sum()), int(down.sum())
