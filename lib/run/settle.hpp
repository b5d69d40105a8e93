#pragma once
#include <cstdint>
#include <string>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

struct SettleResult {
  std::int64_t steps = 0;
  double ke_ratio = 0;  // final mean kinetic energy / (mean mass |g| mean diameter)
  bool converged = false;
  bool skipped = false;  // max_time = 0: not settled at all
};

// Runs under gravity until the SettleSpec criterion holds or its time cap is reached (max_time = 0:
// returns at once).
SettleResult settle(Simulation& sim, const SettleSpec& spec, const std::string& label, bool quiet);

// Mean kinetic energy per particle / (mean mass x |g| x mean diameter): the settle criterion.
double kinetic_ratio(const Simulation& sim);

// Mean number of contacts per particle (particle and wall contacts), 2 N_pairs / N + N_walls / N.
double coordination_number(const Simulation& sim);

}  // namespace dem
