#!/usr/bin/env python3
"""Damping check (thesis §2.4, figs. 2.14-2.15): a sphere released at rest, tangent to a
horizontal wall, oscillates in the contact spring. The exact answer is the damped oscillator
    m·u'' = m·g − kn·u − cn·u',  u(0) = u'(0) = 0,
    cn = 2·γ·sqrt(m·kn),  γ = −ln η / sqrt(π² + ln² η)     (docs/physics.md eq. P14-P15, wall: m* = m),
whose velocity is u'(t) = (g/ω_d)·exp(−γ·ω·t)·sin(ω_d·t), ω = sqrt(kn/m), ω_d = ω·sqrt(1 − γ²):
each half swing's velocity amplitude is η times the previous one. Compares run-stage's --track
CSV with it, writes a summary CSV and a plot of velocity against time; --check fails (exit 1)
if the simulated curve leaves the exact one by more than the tolerance.
"""
import argparse
import csv
import math
import sys

from debian_python import ensure  # noqa: E402

ensure("h5py", "numpy", "matplotlib")

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from post_table import save_atomically, write_csv  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--checkpoint", required=True, help="the checkpoint the drop started from (mass, kn, η, g, Δt)")
    ap.add_argument("--track", required=True, help="run-stage --track CSV of the sphere, every step")
    ap.add_argument("--summary", required=True)
    ap.add_argument("--png", required=True)
    ap.add_argument("--check", type=float, help="largest allowed |v − v_exact| / (g/ω_d)")
    a = ap.parse_args()

    with h5py.File(a.checkpoint, "r") as f:
        m = float(f["particles/mass"][0])
        mat = int(f["particles/material"][0])
        kn = float(f["materials/kn"][mat])
        eta = float(f["materials/restitution"][mat])
        g = float(np.linalg.norm(f["state/gravity"][()]))
        t0 = float(f["state/time"][()])
    rows = list(csv.DictReader(open(a.track)))
    t = np.array([float(r["time_s"]) for r in rows]) - t0
    v = np.array([float(r["vz_m_s"]) for r in rows])
    dt = float(np.median(np.diff(t)))
    # The track's velocities are the leapfrog's half-step values (docs/scene.md): at t − Δt/2.
    tv = t[1:] - dt / 2
    v = v[1:]

    gamma = -math.log(eta) / math.sqrt(math.pi**2 + math.log(eta) ** 2)
    w = math.sqrt(kn / m)
    wd = w * math.sqrt(1 - gamma**2)
    scale = g / wd
    exact = -scale * np.exp(-gamma * w * tv) * np.sin(wd * tv)  # downward velocity is negative
    err = float(np.max(np.abs(v - exact)) / scale)

    # Successive velocity extremes (one per half swing): their ratio is η.
    half = math.pi / wd
    peaks = []
    for k in range(int(tv[-1] / half)):
        sel = (tv >= k * half) & (tv < (k + 1) * half)
        if sel.any():
            peaks.append(float(np.max(np.abs(v[sel]))))
    # Only swings well above the scheme's own error say anything (for η = 1e-7 the second swing
    # is 1e-7 of the first: below it, so the ratio is not measurable and reported as nan).
    ratios = [b / a_ for a_, b in zip(peaks, peaks[1:]) if b > 10 * err * scale]
    measured = float(np.mean(ratios[:4])) if ratios else float("nan")

    rows_out = [
        ("restitution", eta, "-"),
        ("gamma", gamma, "-"),
        ("period_2pi_over_omega_d", 2 * math.pi / wd, "s"),
        ("time_step", dt, "s"),
        ("steps_per_period", 2 * math.pi / wd / dt, "-"),
        ("first_velocity_amplitude", peaks[0] if peaks else float("nan"), "m/s"),
        ("exact_first_velocity_amplitude", scale * math.exp(-gamma * w * math.atan2(math.sqrt(1 - gamma**2), gamma) / wd)
         * math.sqrt(1 - gamma**2), "m/s"),
        ("ratio_of_successive_half_swings", measured, "-"),
        ("max_error_over_g_per_omega_d", err, "-"),
    ]
    write_csv(a.summary, ["key", "value", "unit"], rows_out)
    for k, val, u in rows_out:
        print(f"damping-check: {k} = {val:.6g} {u}")

    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot(tv * 1e3, v * 1e3, lw=1.6, label="dem (half-step velocity)")
    ax.plot(tv * 1e3, exact * 1e3, "k--", lw=0.9, label="exact damped oscillator")
    ax.axhline(0, color="grey", lw=0.6)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("vertical velocity [mm/s]")
    ax.set_title(f"Sphere released on a wall, restitution {eta:g} (thesis fig. 2.{14 if eta > 1e-3 else 15}): "
                 f"half-swing ratio {measured:.4f}", fontsize=8)
    ax.legend(fontsize=8)
    save_atomically(fig, a.png)
    plt.close(fig)
    if a.check is not None and not err <= a.check:
        sys.exit(f"damping-check: FAIL: velocity differs from the exact oscillator by {err:.3g} x g/ω_d (allowed {a.check:g})")


if __name__ == "__main__":
    main()
