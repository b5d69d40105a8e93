#!/usr/bin/env python3
"""Summary of a soak run (bench/soak/soak.sh): restarts, the newest checkpoint, and resident memory
over time. Usage: soak_report.py OUT FAIL MINUTES FINAL_STEP PARTICLES [FREQUENCY] (FAIL: 0 if the
shell checks passed; FREQUENCY: the shaking in Hz, as in bench/soak/scene.toml; without it, or for a
scene that is not shaken, "cycles" of 120 s of wall time).

Memory growth is judged within each run segment (a leak grows with the process's age, and each
restart starts a new process) that starts after the first third of the soak, from the segment's
first minute on. The bed breathes with the shaking: its neighbour lists, and with them the resident
memory, swing by some 20 % within each vibration cycle (seen in the 2026-12-01 run), so a last sample
against a first one measures the phase, not a leak; and a sample taken during a list rebuild holds
the rebuild's scratch lists too; and a restarted process grows its lists to the largest the cycle
needs over its first cycles (capacity is kept). The test compares high levels over whole cycles
instead: the 90th percentile of the samples of the segment's last vibration cycle against that of
the cycle before (cycles in wall seconds from the simulated time in the segment's progress lines);
the last must be within 5 % of the one before. Segments shorter than a minute and two cycles are
listed, not judged. Each segment's level (90th percentile after its first minute) is printed
with its lifetime: a leak would raise it in the processes that lived longest."""
import csv
import glob
import re
import sys


def main():
    out, fail, minutes, final, particles = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
    frequency = float(sys.argv[6]) if len(sys.argv) > 6 and sys.argv[6] else 0.0
    rows = list(csv.DictReader(open(f"{out}/memory.csv")))
    segs = {}
    for r in rows:
        segs.setdefault(int(r["segment"]), []).append((int(r["seconds"]), int(r["rss_kb"])))
    cycle = wall_seconds_per_cycle(out, frequency)
    growth, short = [], []
    for s, v in sorted(segs.items()):
        if v[0][0] < minutes * 60 / 3:
            continue
        v = [x for x in v if x[0] - v[0][0] >= 60]
        if len(v) < 4:
            continue
        span = v[-1][0] - v[0][0]
        if cycle is None or span < 2 * cycle:
            short.append((s, span))
            continue
        end = v[-1][0]
        before = [x[1] for x in v if end - 2 * cycle <= x[0] < end - cycle]
        last = [x[1] for x in v if x[0] >= end - cycle]
        p1, p2 = percentile90(before), percentile90(last)
        growth.append((s, p1, p2, p2 / p1 - 1, span, v[-1][1] / v[0][1] - 1))
    worst = max((g[3] for g in growth), default=0.0)
    print(f"soak: {minutes:g} min, {len(segs)} run segments, each ended by kill -9 ({len(segs) - 1} restarts from the "
          f"newest checkpoint), newest checkpoint at step {final} with {particles} particles")
    for s, v in sorted(segs.items()):
        print(f"soak: segment {s}: {v[0][0]}-{v[-1][0]} s, resident memory {min(x[1] for x in v) / 1024:.0f}-"
              f"{max(x[1] for x in v) / 1024:.0f} MiB")
    # Memory against the state: a leak grows with the process's age, a forming bed with the step.
    windows = {}
    for r in rows:
        windows.setdefault((int(r["segment"]), int(r["step"])), []).append((int(r["seconds"]), int(r["rss_kb"])))
    for (s, step), v in sorted(windows.items()):
        if step >= 0 and len(v) >= 3:
            print(f"soak: segment {s}, newest checkpoint at step {step}: {v[0][0]}-{v[-1][0]} s, "
                  f"{v[0][1] / 1024:.1f} -> {v[-1][1] / 1024:.1f} MiB")
    if cycle is not None and frequency > 0:
        print(f"soak: one vibration cycle ({1 / frequency:g} s simulated) took about {cycle:.0f} s of wall time")
    for s, v in sorted(segs.items()):
        level = [x[1] for x in v if x[0] - v[0][0] >= 60]
        if level:
            print(f"soak: segment {s}: lived {v[-1][0] - v[0][0]} s, level after its first minute (90th percentile) "
                  f"{percentile90(level) / 1024:.1f} MiB")
    for s, p1, p2, g, span, last_first in growth:
        print(f"soak: segment {s}, last vibration cycle against the one before: 90th percentile {p1 / 1024:.1f} -> "
              f"{p2 / 1024:.1f} MiB ({100 * g:+.2f} %; last sample against the first after a minute {100 * last_first:+.2f} %)")
    for s, span in short:
        print(f"soak: segment {s}: {span} s after its first minute, shorter than two vibration cycles: not judged")
    if not growth:
        print("soak: no segment started after the first third and lasted two vibration cycles past its first minute: "
              "memory growth not judged")
    ok = fail == 0 and bool(growth) and worst < 0.05
    print("soak: " + ("PASS" if ok else "FAIL"))
    sys.exit(0 if ok else 1)


def percentile90(values):
    v = sorted(values)
    return v[min(len(v) - 1, int(0.9 * len(v)))]


def wall_seconds_per_cycle(out, frequency):
    """Wall seconds per vibration cycle, from the simulated time of run-stage's progress lines (one
    every 10 s of wall time under soak.sh, which is no terminal), or None if too few."""
    rates = []
    for log in glob.glob(f"{out}/segment_*.log"):
        t = [float(m.group(1)) for m in re.finditer(r"t = ([0-9.eE+-]+) s,", open(log).read())]
        if len(t) >= 3:
            rates.append((t[-1] - t[0]) / (10.0 * (len(t) - 1)))
    if frequency <= 0:
        return 120.0
    rates = [r for r in rates if r > 0]
    if not rates:
        return None
    return 1.0 / frequency / (sum(rates) / len(rates))


if __name__ == "__main__":
    main()
