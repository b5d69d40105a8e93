#!/usr/bin/env python3
"""Markdown table of bench/results/peers_runs.csv: the median loop time of each (scene, code,
processes) and our speed relative to LAMMPS and LIGGGHTS measured in the same session.
Usage: summarize_peers.py RUNS.csv"""
import csv
import datetime
import os
import statistics
import subprocess
import sys


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"


def main(path):
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
    print("Reproduce: `bash bench/run_peer_bench.sh` (every run in `bench/results/peers_runs.csv`).\n")
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
    for scene in sorted({k[0] for k in runs}, key=lambda s: meta[s][0]):
        n, steps = meta[scene]
        for procs in sorted({k[2] for k in runs if k[0] == scene}):
            ours = runs.get((scene, "dem", procs))
            ours_psps = n * steps / statistics.median(ours) if ours else None
            for code in ("dem", "lammps", "liggghts"):
                t = runs.get((scene, code, procs))
                if not t:
                    continue
                med = statistics.median(t)
                psps = n * steps / med
                ratio = "" if code == "dem" or not ours_psps else f"{ours_psps / psps:.2f}x"
                name = {"dem": "dem (ours)", "lammps": "LAMMPS", "liggghts": "LIGGGHTS"}[code]
                print(f"| {scene} | {', '.join(sorted(dates[scene]))} | {steps} | {procs} | {name} | {len(t)} | {med:.2f} ({min(t):.2f}-{max(t):.2f}) | {psps:.3g} | "
                      f"{ratio} | {max(rss[(scene, code, procs)]) / 1024:.0f} |")


if __name__ == "__main__":
    main(sys.argv[1])
