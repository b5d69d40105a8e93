#!/usr/bin/env python3
"""The thesis's dashpot (before issue 30: f_n = k_n u - c_n v_n^(n-1/2), the half-step velocity) on
the binary collisions of bench/binary_collision.hpp, written out for one central contact: the
"before" column of bench/results/restitution.md. The leapfrog and the contact test are the force
loop's (a contact where u > 0 at a whole step); for a central collision the overlap is one
coordinate, so this is the same arithmetic the library did, without the rest of the step.
  python3 bench/old_dashpot_model.py [steps ...]
"""
import math
import sys


def collide(eta, steps, phase, k=1e5, m=1.0, v=0.5):
    l = math.log(eta) if eta > 0 else -math.inf
    g = 1.0 if eta == 0 else -l / math.sqrt(math.pi**2 + l * l)
    c = 2 * g * math.sqrt(m * k)
    w = math.sqrt(k / m)
    wd = w * math.sqrt(1 - g * g)
    tc = math.pi / wd
    dt = tc / steps
    peak_ref = v / w * math.exp(-g * w * math.atan2(math.sqrt(1 - g * g), g) / wd)
    u = -(3 + phase) * v * dt  # overlap (< 0 apart); du/dt = -vn
    vn = -v                      # separating > 0
    t = 0.0
    t_in = None
    peak = 0.0
    dur = 0.0
    for _ in range(int(40 * steps) + 10):
        f = k * u - c * vn if u > 0 else 0.0
        vn += dt * f / m
        before = u
        u -= dt * vn
        t += dt
        peak = max(peak, u)
        if before <= 0 < u:
            t_in = t - dt * u / (u - before)
        if before > 0 >= u:
            dur = t - dt * u / (u - before) - t_in
            break
    return vn / v, dur / tc - 1, peak / peak_ref - 1


def main():
    steps = [float(s) for s in sys.argv[1:]] or [16, 25, 50, 100, 200, 500]
    print("| eta | steps per contact | restitution (worst) | restitution error | contact time error | peak overlap error |")
    print("|---|---|---|---|---|---|")
    for eta in (0.05, 0.1, 0.3, 0.5, 0.9, 1.0):
        for n in steps:
            we = wt = wp = 0.0
            e_at = eta
            for q in range(8):
                e, dtc, dp = collide(eta, n, q / 8)
                de = (e - eta) / eta
                if abs(de) > abs(we):
                    we, e_at = de, e
                if abs(dtc) > abs(wt):
                    wt = dtc
                if abs(dp) > abs(wp):
                    wp = dp
            print(f"| {eta:g} | {n:g} | {e_at:.5f} | {100 * we:+.3f} % | {100 * wt:+.3f} % | {100 * wp:+.3f} % |")


if __name__ == "__main__":
    main()
