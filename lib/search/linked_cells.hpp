#pragma once
// Near-pair search with linked cells (SPEC §4, thesis §3.5, eq. 3.1-3.4): HEAD/LIST over a grid of
// cells with edge >= 2 Rmax + margin, each pair visited once through half of the 26 neighbour
// cells. O(N). The grid spans the particles' bounding box each call, so no domain needs declaring;
// along a periodic axis it spans the period instead, and the neighbour cells wrap around.
// The neighbour list (neighbour_list.hpp) calls it with the skin as margin.
#include <vector>

#include "contact/contact_list.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

class LinkedCells {
 public:
  // Appends every pair closer than touching plus `margin` (|x_i - x_j| < a_i + a_j + margin) to
  // `out`, keyed by ids (key_i < key_j), in no particular order (it depends on the thread count:
  // sort it). A margin lets bonded pairs be found while apart (in tension). Distances are to the
  // nearest image where `box` is periodic; throws InputError when a period is shorter than three
  // cells (2 Rmax + margin each), which the nearest-image search needs.
  void find_near_pairs(const Particles& p, const PeriodicBox& box, std::vector<FoundContact>& out, double margin = 0);
  void find_near_pairs(const Particles& p, std::vector<FoundContact>& out, double margin = 0) {
    find_near_pairs(p, PeriodicBox{}, out, margin);
  }

  // Appends every (particle, wall element) closer than the radius plus `margin` (closest point of
  // the element, eq. 2.4-2.5), keyed (id, element index), in no particular order. Each element
  // visits only the cells its bounding box (grown by the largest radius + margin) overlaps, so a
  // 10,000-triangle mesh costs what its surface covers, not N x elements. Uses the grid of the
  // last find_near_pairs call, which must have been made with the same particles.
  void find_near_walls(const Particles& p, const std::vector<WallGeometry>& walls, std::vector<FoundContact>& out, double margin);

 private:
  void bin(const Particles& p, const PeriodicBox& box, double margin);  // the grid of cells and HEAD/LIST
  long cell_coord(double x, int d) const;

  std::vector<int> head_, next_;
  Vec3 lo_ = Vec3::Zero();
  Vec3 edge_ = Vec3::Zero();  // per axis: a period is divided into whole cells
  double rmax_ = 0;
  long dims_[3] = {0, 0, 0};
  std::vector<std::vector<FoundContact>> per_thread_;
};

}  // namespace dem
