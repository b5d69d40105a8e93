#!/usr/bin/env bash
# The scripts find a Python with h5py (issue 35, item 8): run by an interpreter that lacks h5py
# (Debian's own, with its site packages switched off by -S), a script reruns itself with
# /usr/bin/python3 and says so; where no Python has the modules, it names the packages to install.
# The plots' titles and axes are words with units, not the CSV's column names.
set -u
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/check_lib.sh"  # check NAME EXPECTED_CODE PATTERN -- command...
/usr/bin/python3 -c "import h5py, numpy, matplotlib" || { echo "FAIL /usr/bin/python3 lacks h5py, numpy or matplotlib (apt-get install python3-h5py python3-matplotlib)"; exit 1; }
for s in damping_check segregation_report segregation_sweep; do
  check "$s.py without h5py reruns with /usr/bin/python3" 0 "lacks h5py.*running with /usr/bin/python3" -- /usr/bin/python3 -S "$src/scripts/$s.py" --help
  grep -q "^usage: $s.py" "$tmp/out" || { echo "FAIL $s.py: no usage after the rerun"; fail=1; }
done
check "plot_stress.py without numpy reruns" 1 "running with /usr/bin/python3" -- /usr/bin/python3 -S "$src/scripts/plot_stress.py"
grep -q "^usage: plot_stress.py" "$tmp/out" || { echo "FAIL plot_stress.py: no usage after the rerun"; fail=1; }
check "no Python with h5py: says what to install" 1 "apt-get install python3-h5py python3-numpy python3-matplotlib" -- \
  env DEM_PYTHON_RERUN=1 /usr/bin/python3 -S "$src/scripts/damping_check.py" --help

# Plots of post-macro's tables (the format of lib/io/post_output.cpp): titles and axes in words.
printf '%s\n' "# stress profile of /long/path/out/shaken.h5 (t = 0.5 s) over box [0 0 0] to [0.02 0.02 0.012] m: contact stress (no kinetic part) in Pa" \
  "z_centre,z_lo,z_hi,count,solid_fraction,sxx,sxy,sxz,syx,syy,syz,szx,szy,szz,pressure,q" \
  "0.0015,0,0.003,10,0.5,-10,0,0,0,-11,0,0,0,-30,17,20" "0.0045,0.003,0.006,8,0.4,-5,0,0,0,-6,0,0,0,-12,7.6,6" > "$tmp/stress.csv"
printf '%s\n' "# displacement profile from /a/settled.h5 (t = 0 s) to /a/shaken.h5 (t = 0.5 s); lengths in m" \
  "z_centre,count,mean_ux,mean_uy,mean_uz,mean_norm_u" "0.0015,10,0.0001,0,-0.0002,0.0003" "0.0045,8,0,0.0001,0.0001,0.0002" > "$tmp/profile.csv"
/usr/bin/python3 "$src/scripts/plot_stress.py" "$tmp/stress.csv" "$tmp/stress.png" && \
  /usr/bin/python3 "$src/scripts/plot_profile.py" "$tmp/profile.csv" "$tmp/profile.png" && [ -s "$tmp/stress.png" ] && [ -s "$tmp/profile.png" ] \
  && echo "ok   plot_stress.py and plot_profile.py draw their PNGs" || { echo "FAIL plots not drawn"; fail=1; }
check "plot words: no column names, units on the axes" 0 "words ok" -- /usr/bin/python3 - "$src/scripts" "$tmp" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import plot_profile, plot_stress
from post_table import read_table
raw = ("z_centre", "mean_ux", "mean_norm_u", "sxx", "szz", "count", "/long/path", "/a/")
for mod, csv, arg in ((plot_stress, "stress.csv", None), (plot_profile, "profile.csv", "z")):
    title, header, _, _ = read_table(f"{sys.argv[2]}/{csv}")
    w = mod.labels(title, header if arg is None else arg)
    for key, text in w.items():
        assert not any(r in text for r in raw), (key, text)
    assert "[mm]" in w["ylabel"] and ("[Pa]" in w["xlabel"] or "[mm]" in w["xlabel"]), w
    assert w["title"][0].isupper() and "_" not in w["title"], w["title"]
    print(w["title"], "|", w["subtitle"], "|", w["xlabel"], "|", w["ylabel"])
print("words ok")
PY
exit $fail
