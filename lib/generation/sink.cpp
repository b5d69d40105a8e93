#include "generation/sink.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "generation/fill.hpp"

namespace dem {

std::size_t sink_due(Simulation& sim, const SinkSpec& spec, std::int64_t stage_step, SinkTotals& totals) {
  if (stage_step % spec.every != 0) return 0;
  const Particles& p = sim.particles;
  if (!spec.region.any_inside(p.x)) return 0;  // most events: one pass, nothing allocated
  const std::vector<char> in = centres_inside(p, spec.region);
  std::vector<std::pair<Index, double>> gone;  // (id, mass) of the particles in the region
  for (std::size_t k = 0; k < p.size(); ++k)
    if (in[k]) gone.emplace_back(p.id[k], p.mass[k]);
  if (gone.empty()) return 0;
  // Summed in id order, not storage order: the total does not depend on how the storage was sorted.
  std::sort(gone.begin(), gone.end());
  for (const auto& [id, m] : gone) totals.mass += m;
  totals.count += static_cast<std::int64_t>(gone.size());
  remove_marked(sim, in);  // after a step: the lists filtered, no neighbour search (Simulation::remove_from_lists)
  sim.release_contact_views();
  return gone.size();
}

}  // namespace dem
