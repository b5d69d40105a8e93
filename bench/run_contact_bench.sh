#!/usr/bin/env bash
# Builds and runs the contact-physics benchmarks; writes bench/results/contact.md.
# Usage: bash bench/run_contact_bench.sh   (from the repository root; about 5 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
make -f Makefile.cases build > /dev/null
out=bench/results/contact.md
{
  echo "# Contact physics: speed against error, and the price of each option"
  echo
  echo "Measured $(date -u +%Y-%m-%d) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
  echo "dem at commit $(build/tools/run-stage --version | awk '{print $NF}' | tr -d ')'), g++ -O3. Reproduce: \`bash bench/run_contact_bench.sh\`."
  echo
  echo "## Speed against error (FRAC of docs/physics.md eq. P5)"
  echo
  echo "Binary collision of two 1 mm glass spheres (k_n = 2000 N/m) against the analytic restitution"
  echo "eta and damped half-period pi/omega_d; cost per simulated second of the 10,000-sphere settle"
  echo "scene of ../shared/peers (closed box, friction 0.5, eta = 0.5), all threads."
  echo
  build/bench/contact_bench frac-sweep
  echo
  echo "## The price of each physics option (same packing: the settle scene after 0.1 s; 300 steps each)"
  echo
  build/bench/contact_bench variants
  echo
  echo "Contacts: particle-particle plus particle-wall at the end of the run. Without bonds the liu"
  echo "law runs the cundall force loop (a scene pays only for what it uses); with bonds, liu and"
  echo "mendes run their own (four contacts at a time, as every law, rolling included),"
  echo "whose price the last column shows; single runs differ by about 5 % on this machine (compare the first two"
  echo "rows, which do the same work). Particle-wall candidates are listed with the neighbour list"
  echo "(rebuilt only when something moved half the skin), so walls that touch nothing cost almost nothing."
  echo "The hertz rows use E = 5e8 Pa and nu = 0.3 (as stiff as kn = 2000 N/m where a bead carries its"
  echo "weight), the rolling rows mu_r = 0.1; the step is the cundall rows' for all, so the price is per step."
  echo "Our speed beside LAMMPS and LIGGGHTS: bench/results/peers.md (bash bench/run_peer_bench.sh)."
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
