#pragma once
// What the step benchmarks (settle_bench, chute_bench) print for a timed run: one line that
// bench/run_peer_bench.sh parses.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "contact/model_table.hpp"
#include "sim/simulation.hpp"

namespace dem::bench {

inline long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

inline double rotational_energy(const Simulation& sim) {
  double e = 0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) e += 0.5 * sim.particles.inertia(i) * sim.particles.w[i].squaredNorm();
  return e;
}

// walls, particles, steps, threads, loop seconds, particle-steps per second, contacts, kinetic
// energies, peak resident memory (and its increase since `rss_before`), the laws of the first
// material with itself (normal/tangential/rolling).
inline void print_run(const Simulation& sim, long steps, int threads, double loop, long rss_before) {
  const long rss = peak_rss_kb();
  const PairParams& p = sim.materials.pair(0, 0);
  std::printf("walls %zu particles %zu steps %ld threads %d loop_s %.4f psps %.4g contacts %zu ke %.10g rke %.10g rss_kb %ld rss_increase_kb %ld "
              "laws %s/%s/%s\n",
              sim.walls.size(), sim.particles.size(), steps, threads, loop, sim.particles.size() * static_cast<double>(steps) / loop,
              sim.pair_contact_count() + sim.wall_contact_count(), sim.kinetic_energy() - rotational_energy(sim),
              rotational_energy(sim), rss, rss - rss_before, std::string(normal_law_name(p.law)).c_str(),
              std::string(tangential_law_name(p.tangential)).c_str(), std::string(rolling_law_name(p.rolling)).c_str());
}

// Runs `steps` steps of `sim` on `threads` threads (set before the scene was built, as the
// caller does) and prints the line above, timing the steps only. As run-stage does, the steps
// do not keep the pair contacts' forces (SimParams::keep_pair_results: nothing reads them).
inline void timed_run(Simulation& sim, long steps, int threads, long rss_before) {
  sim.params.keep_pair_results = false;
  const auto t0 = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; ++s) sim.advance();
  const double loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_run(sim, steps, threads, loop, rss_before);
}

}  // namespace dem::bench
