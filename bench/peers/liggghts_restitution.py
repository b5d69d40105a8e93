#!/usr/bin/python3
"""The restitution LIGGGHTS 3.8 realises in a head-on Hertz impact (bench/peers/in.impact_hertz.liggghts)
against the asked e, at steps of t_c/N (t_c the undamped Hertz contact's duration), for the
table of bench/results/dashpot.md. Prints, per e, the relative error at N = 50 (the worst of four
phases of the first touch within a step) and at N = 20 and 200.

  python3 bench/peers/liggghts_restitution.py      (about 15 s; needs Debian's liggghts)

With --test-reference: the realised restitution itself, to full precision, of the impacts that
tests/test_hertz.cpp's Hertz.ExplicitDashpotReboundsAsLIGGGHTS runs with our explicit dashpot
(eq. D7) and compares with these numbers: e 0.1, 0.3, 0.5, 0.9 at N = 20 and 50, the first touch
at fractions 0 and 0.5 of the fourth step (the gap (3 + phase) V dt, as bench/binary_collision.hpp
places it).
"""
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
E, NU, RHO, R, V = 5e6, 0.3, 2500.0, 1e-3, 0.2  # the input's material; the approach speed [m/s]
M_EFF = RHO * 4 / 3 * math.pi * R**3 / 2
R_EFF, E_EFF = R / 2, E / (2 * (1 - NU**2))
DELTA_MAX = (15 * M_EFF * V * V / (16 * E_EFF * math.sqrt(R_EFF))) ** 0.4  # Hertz's peak overlap
T_C = 2.9432751843247047 * DELTA_MAX / V  # Hertz's contact time


def restitution(e, steps_per_contact, phase, steps_before=None):
    """The realised restitution of one impact; phase: where within a step the touch falls, after
    1e-4 m of gap, or after steps_before whole steps where given."""
    dt = T_C / steps_per_contact
    gap = (steps_before + phase) * V * dt if steps_before is not None else 1e-4 + phase * V * dt
    x = R + gap / 2
    nsteps = int((gap / V + 2 * T_C) / dt) + 10
    out = subprocess.run(["liggghts", "-in", os.path.join(HERE, "in.impact_hertz.liggghts"), "-log", "none", "-echo", "none",
                          "-var", "e", str(e), "-var", "dt", repr(dt), "-var", "nsteps", str(nsteps), "-var", "x", repr(x)],
                         capture_output=True, text=True, check=True).stdout
    v1, v2 = map(float, re.search(r"RESULT (\S+) (\S+)", out).groups())
    return (v2 - v1) / V


def error(e, steps_per_contact, phase):
    """Realised restitution / e - 1 for one impact."""
    return restitution(e, steps_per_contact, phase) / e - 1


def main():
    if "--test-reference" in sys.argv:
        for e in (0.1, 0.3, 0.5, 0.9):
            for n in (20, 50):
                for phase in (0.0, 0.5):
                    print(f"{{{e}, {n}, {phase}, {restitution(e, n, phase, steps_before=3)!r}}},", flush=True)
        return
    print(f"t_c = {T_C:.4e} s")
    for e in (0.06, 0.1, 0.3, 0.5, 0.7, 0.9):  # LIGGGHTS takes e > 0.05 only
        worst = max((error(e, 50, ph) for ph in (0.0, 0.25, 0.5, 0.75)), key=abs)
        print(f"e {e}: N=50 worst {worst:+.2e}  N=20 {error(e, 20, 0.3):+.2e}  N=200 {error(e, 200, 0.3):+.2e}", flush=True)


if __name__ == "__main__":
    main()
