#!/usr/bin/env python3
"""Summary of a soak run (bench/soak/soak.sh): restarts, the newest checkpoint, and resident memory
over time. Usage: soak_report.py OUT FAIL MINUTES FINAL_STEP PARTICLES (FAIL: 0 if the shell
checks passed). Memory growth is judged within each run segment that starts after the first third
of the soak (the bed forms before that, and its contacts and lists grow with it), from the
segment's first minute on: the last sample must be within 5 % of the first."""
import csv
import sys


def main():
    out, fail, minutes, final, particles = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
    rows = list(csv.DictReader(open(f"{out}/memory.csv")))
    segs = {}
    for r in rows:
        segs.setdefault(int(r["segment"]), []).append((int(r["seconds"]), int(r["rss_kb"])))
    growth = []
    for s, v in sorted(segs.items()):
        if v[0][0] < minutes * 60 / 3:
            continue
        v = [x for x in v if x[0] - v[0][0] >= 60]
        if len(v) >= 2:
            growth.append((s, v[0][1], v[-1][1], v[-1][1] / v[0][1] - 1))
    worst = max((abs(g[3]) for g in growth), default=0.0)
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
    for s, first, last, g in growth:
        print(f"soak: segment {s} after its first minute: {first / 1024:.1f} -> {last / 1024:.1f} MiB ({100 * g:+.2f} %)")
    if not growth:
        print("soak: no segment started after the first third and lasted over a minute: memory growth not judged")
    ok = fail == 0 and worst < 0.05
    print("soak: " + ("PASS" if ok else "FAIL"))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
