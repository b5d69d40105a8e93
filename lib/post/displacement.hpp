#pragma once
// Displacement between two states, matched by particle id (SPEC §11).
#include <cstddef>
#include <string>
#include <vector>

#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

struct DisplacementField {
  std::vector<Vec3> u;          // per particle of the current state; NaN where the id is not in the reference
  std::size_t matched = 0;      // particles present in both states
  std::size_t removed = 0;      // in the reference only
  std::size_t added = 0;        // in the current state only
};

// Positions are unwrapped across periodic boundaries (each state's own `box`), so a particle that
// left at one side and re-entered at the other has moved by its path, not by the period.
DisplacementField displacement_by_id(const Particles& reference, const Particles& current, const PeriodicBox& reference_box = {},
                                     const PeriodicBox& current_box = {});

// Mean displacement in `bins` slabs along `axis` (0 = x, 1 = y, 2 = z) of the current positions.
struct ProfileRow {
  double centre;  // [m]
  std::size_t count;
  Vec3 mean_u;     // [m]
  double mean_norm;  // mean |u| [m]
};
std::vector<ProfileRow> displacement_profile(const Particles& current, const DisplacementField& d, int axis, int bins);

}  // namespace dem
