#!/usr/bin/env bash
# Writes lammps.csv, the reference of tests/test_mindlin.cpp (Chung & Ooi's test 4 spheres in
# LAMMPS): the rebound velocity and spin of one of two alumina spheres that meet at 3.9 m/s, at
# each angle from the line of centres (in.oblique).
# Needs LAMMPS (Debian: apt-get install lammps; made with 20220106). Run from this folder.
set -euo pipefail
cd "$(dirname "$0")"
dt=5e-8       # t_c / 190 at normal incidence (t_c = 9.5 us)
steps=2000    # 100 us: the spheres part within 16 us at every angle
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "theta_deg,vx,vz,omega_y" > lammps.csv
for theta in 1 2 4 6 8 10 15 20 25 30 40 50 60 70 80 85; do
  lmp -log none -screen none -var theta "$theta" -var dt "$dt" -var steps "$steps" -var out "$tmp/$theta.dump" -in in.oblique
  read -r vx vz wy <<< "$(tail -n 1 "$tmp/$theta.dump")"  # the dump's last row: the atom after the run
  echo "$theta,$vx,$vz,$wy" >> lammps.csv
done
echo "wrote $(pwd)/lammps.csv"
