#pragma once
// Near-pair search with linked cells (SPEC §4, thesis §3.5, eq. 3.1-3.4): HEAD/LIST over a grid of
// cells with edge >= 2 Rmax + margin, each pair visited once through half of the 26 neighbour
// cells. O(N). The grid spans the particles' bounding box each call, so no domain needs declaring.
// The neighbour list (neighbour_list.hpp) calls it with the skin as margin.
#include <vector>

#include "contact/contact_list.hpp"
#include "state/particles.hpp"

namespace dem {

class LinkedCells {
 public:
  // Appends every pair closer than touching plus `margin` (|x_i - x_j| < a_i + a_j + margin) to
  // `out`, keyed by ids (key_i < key_j), in no particular order (it depends on the thread count:
  // sort it). A margin lets bonded pairs be found while apart (in tension).
  void find_near_pairs(const Particles& p, std::vector<FoundContact>& out, double margin = 0);

 private:
  std::vector<int> head_, next_;
  std::vector<std::vector<FoundContact>> per_thread_;
};

}  // namespace dem
