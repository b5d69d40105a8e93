#!/usr/bin/env python3
"""Markdown table of bench/results/peers_runs.csv: the median loop time of each (scene, code,
processes) and our speed relative to LAMMPS and LIGGGHTS measured in the same session.
A runs file with Hertz models (peers_hertz_runs.csv) gets the Hertz table: issue 31's targets and
the rolling resistance's cost. Usage: summarize_peers.py RUNS.csv"""
import csv
import datetime
import os
import statistics
import subprocess
import sys


# run_peer_bench.sh pins one-process runs since 2026-12-06 (peers_hertz.md, "The machine's two cores").
PINNED = ("One process: every code pinned to the same core (`taskset -c $PIN_CPU`, default 0) in runs "
          "since 2026-12-06, left to the scheduler before.")

def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"


def scene_procs(runs, meta, procs_at):
    """(scene, particles, steps, procs) for each scene in size order and each process count it was
    run with; procs_at: the place of the process count in the runs' keys."""
    for scene in sorted({k[0] for k in runs}, key=lambda s: meta[s][0]):
        n, steps = meta[scene]
        for procs in sorted({k[procs_at] for k in runs if k[0] == scene}):
            yield scene, n, steps, procs


def spread(t):
    """A run list's median with its range, as the tables print it."""
    return f"{statistics.median(t):.2f} ({min(t):.2f}-{max(t):.2f})"


def main(path):
    rows = list(csv.DictReader(open(path)))
    if any((r.get("model") or "linear") != "linear" for r in rows):
        return hertz(rows)
    runs = {}
    rss = {}
    dates = {}
    for r in csv.DictReader(open(path)):
        key = (r["scene"], r["code"], int(r["procs"]))
        runs.setdefault(key, []).append(float(r["loop_s"]))
        rss.setdefault(key, []).append(int(r["peak_rss_kb"]))
        dates.setdefault(r["scene"], set()).add(r.get("date") or "?")
    meta = {(r["scene"]): (int(r["particles"]), int(r["steps"])) for r in csv.DictReader(open(path))}
    cpu = sh("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2").strip()
    versions = sh("dpkg-query -W -f '${Package} ${Version}; ' lammps liggghts openmpi-bin")
    dem = sh(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "tools", "run-stage") + " --version")
    print("# Our code beside LAMMPS and LIGGGHTS: settle and chute scenes\n")
    print(f"Written {datetime.date.today()} on {os.cpu_count()} cores ({cpu}); each scene's runs in one session, interleaved")
    print("(the date column); ratios compare codes within a scene's session only;")
    print(f"{dem} (g++ -O3 since 2026-11-24, -O2 before; OpenMP threads); Debian {versions.rstrip('; ')} (MPI processes).")
    print(PINNED)
    print("Reproduce: `bash bench/run_peer_bench.sh` (every run in `bench/results/peers_runs.csv`).")
    print("Hertz-Mindlin and rolling resistance in the same scenes: [peers_hertz.md](peers_hertz.md).\n")
    print("Settle (`bench/settle_scene.hpp`, inputs `bench/peers/in.settle.*`): spheres of radius 1 mm on a loose")
    print("lattice with random velocities fall into a closed box of six walls; linear spring-dashpot,")
    print("kn = 2000 N/m, kt = 2/7 kn, friction 0.5, damping as LAMMPS's gamma_n = 8421.7 1/s x m_eff,")
    print("dt = 1e-5 s, skin 0.2 mm, neighbour check every step; mostly free fall.")
    print("Chute (`bench/chute_scene.hpp`, inputs `bench/peers/in.chute.*`): the physics of LAMMPS's chute-flow")
    print("benchmark (32,000 spheres, gran/hooke/history kn = 2e5, gamma_n = 50, friction 0.5, periodic in x")
    print("and y, gravity tilted 26 degrees, a frozen rough base; LJ units, dt = 1e-4, skin 0.1) from a")
    print("regenerated initial state (a touching lattice with random velocities that collapses and flows;")
    print("25,511 contacts among the 32,000 spheres after 2,000 steps, against 4,153 among 100,000 in settle).")
    print("PSPS = particles x steps / loop time (median of the runs; loop time excludes setup, as LAMMPS's")
    print("`Loop time`). Peak RSS: largest process.\n")
    print("| scene | measured | steps | procs | code | runs | loop s (median) | PSPS | ours / this code | peak RSS MB |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene, n, steps, procs in scene_procs(runs, meta, 2):
        ours = runs.get((scene, "dem", procs))
        ours_psps = n * steps / statistics.median(ours) if ours else None
        for code in ("dem", "lammps", "liggghts"):
            t = runs.get((scene, code, procs))
            if not t:
                continue
            psps = n * steps / statistics.median(t)
            ratio = "" if code == "dem" or not ours_psps else f"{ours_psps / psps:.2f}x"
            print(f"| {scene} | {', '.join(sorted(dates[scene]))} | {steps} | {procs} | {NAMES[code]} | {len(t)} | {spread(t)} | {psps:.3g} | "
                  f"{ratio} | {max(rss[(scene, code, procs)]) / 1024:.0f} |")


TARGETS = {"liggghts": 2.0, "lammps": 1.5}  # issue 31: at least 2x LIGGGHTS, 1.5x LAMMPS per core
NAMES = {"dem": "dem (ours)", "lammps": "LAMMPS", "liggghts": "LIGGGHTS"}


def verdict(ratio, code):
    """Issue 31's target against `code` for our speed ratio: met, or missed by how much."""
    return "met" if ratio >= TARGETS[code] else f"missed ({ratio / TARGETS[code] - 1:+.1%})"


def hertz(rows):
    """The Hertz-Mindlin table (peers_hertz_runs.csv): medians, our ratio against each peer with
    issue 31's target, and each code's rolling resistance cost over Hertz alone."""
    runs, rss, dates, meta = {}, {}, {}, {}
    for r in rows:
        key = (r["scene"], r["model"], r["code"], int(r["procs"]))
        runs.setdefault(key, []).append(float(r["loop_s"]))
        rss.setdefault(key, []).append(int(r["peak_rss_kb"]))
        dates.setdefault(r["scene"], set()).add(r["date"])
        meta[r["scene"]] = (int(r["particles"]), int(r["steps"]))
    cpu = sh("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2").strip()
    versions = sh("dpkg-query -W -f '${Package} ${Version}; ' lammps liggghts openmpi-bin")
    dem = sh(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "tools", "run-stage") + " --version")
    print("# Our code beside LAMMPS and LIGGGHTS: Hertz-Mindlin and rolling resistance\n")
    print(f"Written {datetime.date.today()} on {os.cpu_count()} cores ({cpu}); each scene's runs in one session, interleaved;")
    print(f"{dem} (OpenMP threads); Debian {versions.rstrip('; ')} (MPI processes).")
    print(PINNED)
    print("Reproduce: `bash bench/run_peer_bench.sh 3 \"settle:10000:20000 chute:32000:2000\" \"hertz hertz-rolling hertz-explicit hertz-rolling-explicit\"`")
    print("(every run in `bench/results/peers_hertz_runs.csv`). The models, the material values and how each")
    print("code is told the same physics: the notes below the tables (and `bench/hertz_models.hpp`,")
    print("`bench/peers/in.*_hertz.*`). PSPS = particles x steps / loop time (median of the runs, setup")
    print("excluded). Target (issue 31): ours at least 2x LIGGGHTS and 1.5x LAMMPS at the same number of cores.\n")
    print("| scene | model | measured | steps | procs | code | runs | loop s (median, range) | PSPS | ours / this code | target | peak RSS MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    models = [m for m in ("hertz", "hertz-rolling") if any(k[1] == m for k in runs)]
    for scene, n, steps, procs in scene_procs(runs, meta, 3):
        for model in models:
            ours = runs.get((scene, model, "dem", procs))
            for code in ("dem", "lammps", "liggghts"):
                t = runs.get((scene, model, code, procs))
                if not t:
                    continue
                med = statistics.median(t)
                ratio = target = ""
                if code != "dem" and ours:
                    r = med / statistics.median(ours)
                    ratio = f"{r:.2f}x"
                    target = f"{TARGETS[code]}x: " + verdict(r, code)
                print(f"| {scene} | {model} | {', '.join(sorted(dates[scene]))} | {steps} | {procs} | {NAMES[code]} | {len(t)} | "
                      f"{spread(t)} | {n * steps / med:.3g} | {ratio} | {target} | {max(rss[(scene, model, code, procs)]) / 1024:.0f} |")
    if len(models) == 2:
        print("\nRolling resistance over Hertz alone (median loop time of hertz-rolling / hertz - 1; issue 31: at most +15 % for ours):\n")
        print("| scene | procs | dem (ours) | LAMMPS | LIGGGHTS |")
        print("|---|---|---|---|---|")
        for scene, _, _, procs in scene_procs(runs, meta, 3):
            cells = []
            for code in ("dem", "lammps", "liggghts"):
                a, b = runs.get((scene, "hertz", code, procs)), runs.get((scene, "hertz-rolling", code, procs))
                cells.append(f"{statistics.median(b) / statistics.median(a) - 1:+.1%}" if a and b else "")
            print(f"| {scene} | {procs} | " + " | ".join(cells) + " |")
    explicit = [m for m in ("hertz-explicit", "hertz-rolling-explicit") if any(k[1] == m for k in runs)]
    if explicit:
        print("\nOurs with the explicit dashpot (`explicit_dashpot = true`, docs/contact-laws.md eq. D7: the dashpot as")
        print("LIGGGHTS and LAMMPS integrate it, its restitution first order in the step), against the same session's")
        print("peer rows of the model without the suffix (the peers' inputs do not change), and against ours with the")
        print("dashpot through the step (eq. D1-D6, the rows above):\n")
        print("| scene | model | procs | runs | loop s (median, range) | PSPS | / LIGGGHTS (target 2x) | / LAMMPS (target 1.5x) | against D1-D6 |")
        print("|---|---|---|---|---|---|---|---|---|")
        for scene, n, steps, procs in scene_procs(runs, meta, 3):
            for model in explicit:
                t = runs.get((scene, model, "dem", procs))
                if not t:
                    continue
                med = statistics.median(t)
                base = model[:-len("-explicit")]
                cells = []
                for code in ("liggghts", "lammps"):
                    peer = runs.get((scene, base, code, procs))
                    r = statistics.median(peer) / med if peer else None
                    cells.append(f"{r:.2f}x: " + verdict(r, code) if peer else "")
                ours = runs.get((scene, base, "dem", procs))
                against = f"{med / statistics.median(ours) - 1:+.1%}" if ours else ""
                print(f"| {scene} | {model} | {procs} | {len(t)} | {spread(t)} | {n * steps / med:.3g} | "
                      + " | ".join(cells) + f" | {against} |")
    print(HERTZ_NOTES)


HERTZ_NOTES = """
## The same physics in three codes

Models: ours `law = "hertz"`, `tangential = "mindlin"`, `rolling = "none"` or `"epsd2"`
(`bench/hertz_models.hpp`); LIGGGHTS `pair_style gran model hertz tangential history
rolling_friction off|epsd2` with `fix property/global youngsModulus poissonsRatio
coefficientRestitution coefficientFriction coefficientRollingFriction`; LAMMPS `pair_style
granular`, `pair_coeff * * hertz/material E e_L nu tangential mindlin_rescale/force NULL 0.9075
mu damping tsuji rolling none|sds k_roll 0 mu_r`. Walls (settle): the same model on six planes
(LIGGGHTS `fix wall/gran ... primitive`, LAMMPS `fix wall/gran granular ...`), a wall being a body
of infinite radius and mass in all three.

| | settle (SI) | chute (LJ units) |
|---|---|---|
| E, nu | 5e6 Pa, 0.3 | 2e7, 0.3 (E* = 1.1e7: 4/3 E* sqrt(R* u) = kn = 2e5 at u = 7.5e-4 d) |
| restitution e (ours, LIGGGHTS) | 0.5 | 0.9 |
| LAMMPS tsuji e_L (same dashpot) | 0.36665 | 0.86212 |
| friction | 0.5 | 0.5 |
| rolling friction mu_r | 0.1 | 0.1 |
| LAMMPS k_roll (sds) | 320 N/m | 9.05e4 |
| dt | 5e-6 s (pair t_c/54 at 1 m/s) | 1e-4 (t_c/34 at speed 1; linear scene: t_c/36) |
| particles, skin | 10,000 R = 1 mm, 0.2 mm | 32,000 d = 1, 0.1 |

- Normal: Hertz f = 4/3 E* sqrt(R*) u^(3/2) in all three. Dashpot: ours and LIGGGHTS's are
  c_n = 2 sqrt(5/6) beta(e) sqrt(m* S_n), S_n = 2 E* sqrt(R* u) (docs/contact-laws.md eq. H6-H7).
  LAMMPS's `tsuji` is alpha(e) sqrt(m* 4/3 E* sqrt(R* u)) with Tsuji's polynomial alpha: the
  same form, so LAMMPS is given the e_L whose alpha(e_L) = sqrt(5) beta(e): the same c_n.
- Tangential: k_t = 8 G* sqrt(R* u) in all three. Dashpot: LIGGGHTS 2 sqrt(5/6) beta sqrt(m* k_t);
  ours eq. H10 (with 2/7 m*) at tangential restitution chosen so that it is the same
  (gamma_t = sqrt(7/2) gamma); LAMMPS x_gammat c_n with x_gammat = sqrt(k_t / S_n) = 0.9075.
  Springs: ours incremental force scaled with the contact radius on unloading (eq. H11) = LAMMPS
  `mindlin_rescale/force`; LIGGGHTS keeps the displacement (f = -k_t(a) s), which differs while
  the contact loads. Not exactly the same law; the same work per contact.
- Rolling: ours and LIGGGHTS's `epsd2` are k_r = k_t R*^2 (growing with the contact), capped at
  mu_r R* f_n, no rolling dashpot. LAMMPS has no such model: `rolling sds` is a spring of constant
  stiffness k_roll R*^2 (k_roll = our k_t at an overlap of 1e-5 m (settle) or 1e-4 (chute)), no
  damping, capped at mu_r R* |f_n|: the same cost, not the same law.
- Chute base: frozen spheres; LAMMPS and LIGGGHTS take m* = m for a sphere on a frozen one, ours
  m/2, so our base pair gets restitutions with sqrt(2) larger damping ratios (the same dashpot).
- LIGGGHTS 3.8 warns for `model hertz tangential history rolling_friction epsd2`: "not located in
  any whitelist ... will be run in an unoptimized version (increasing runtime by up to 20%)": its
  hertz-rolling rows are its generic (slower) path, as any LIGGGHTS user with epsd2 gets.
- Sanity (2,000 chute steps, one core): kinetic energy 396.25 (ours), 396.46 (LAMMPS), 396.06
  (LIGGGHTS); with rolling 387.76, 388.25, 387.63; rotational 0.240, 0.241, 0.245. Settle, 4,000
  steps: 1.7785e-3 J, 1.7787e-3 J, 1.7789e-3 J (rolling: 1.7673e-3, 1.7697e-3, 1.7672e-3). Ours with
  the explicit dashpot (96ba07b): 396.21 (chute), 1.7783e-3 J (settle).
"""


if __name__ == "__main__":
    main(sys.argv[1])
