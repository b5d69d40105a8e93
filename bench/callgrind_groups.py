#!/usr/bin/env python3
"""Instructions per particle-step of two callgrind profiles of one bench run, in total and by group
of functions (by name), for bench/run_summation_bench.sh.
Usage: callgrind_groups.py BEFORE.cg:AFTER.cg:STEPS:PARTICLES ..."""
import subprocess, re, sys
cats = [("contact law", r"law|pair_chunk"), ("summing loads (sum pass, finish_block)", r"sum_pair_contacts|finish_block|block_forces"),
        ("walls", r"wall|closest_point"), ("finding contacts (pass 1)", r"find_contacts"),
        ("integration", r"move_four|four_at_a_time|largest_move|move_"), ("neighbour list", r"find_near_pairs|maybe_near|linked|sort|index_contacts|carry|place_by"),
        ("energy check", r"mechanical_energy")]
def groups(f):
    out = subprocess.run(["callgrind_annotate", "--threshold=100", f], capture_output=True, text=True).stdout
    tot = {c: 0 for c, _ in cats}; tot["other"] = 0; total = 0
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(.*)", line)
        if not m: continue
        n = int(m.group(1).replace(",", "")); name = m.group(2)
        if "PROGRAM TOTALS" in name: total = n; continue
        for c, rx in cats:
            if re.search(rx, name.split("[")[0]): tot[c] += n; break
        else: tot["other"] += n
    return total, tot
for pair in sys.argv[1:]:
    a, b, steps, n = pair.split(":")
    ta, ga = groups(a); tb, gb = groups(b)
    per = int(steps) * int(n)
    print(f"{pair}: total {ta/per:.1f} -> {tb/per:.1f} instr per particle-step ({(tb/ta-1)*100:+.1f} %)")
    for c in ga: print(f"   {c:40s} {ga[c]/per:7.1f} {gb[c]/per:7.1f}")
