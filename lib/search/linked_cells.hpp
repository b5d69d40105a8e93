#pragma once
// Near-pair search with linked cells (SPEC §4, thesis §3.5, eq. 3.1-3.4): the particles binned
// into a grid of cells with edge >= 2 Rmax + margin (eq. 3.1's HEAD/LIST, stored as each cell's
// run of slots), each pair visited once through half of the 26 neighbour cells. O(N). The grid spans
// the particles' bounding box each call, so no domain needs declaring; along a periodic axis it
// spans the period instead, and the neighbour cells wrap around.
// The neighbour list (neighbour_list.hpp) calls it with the skin as margin.
#include <vector>

#include "contact/contact_list.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

// What one thread of a search finds, on cache lines of its own: threads appending to vectors whose
// sizes share a line would pass it back and forth at every pair found.
struct alignas(64) SearchPart {
  std::vector<FoundContact> found;
  // How many it found at the last search of pairs and of walls: the room reserved at the next
  // (grown by push_back instead, each search copied its pairs over several times).
  std::size_t last_pairs = 0, last_walls = 0;
};

class LinkedCells {
 public:
  // Sets `out` to every pair closer than touching plus `margin` (|x_i - x_j| < a_i + a_j + margin),
  // keyed by ids (key_i < key_j), grouped by the smaller of the two storage slots in slot order,
  // key order within a group: the order place_by_storage gives (contact/contact_list.hpp), whatever
  // the thread count, with no sort of the whole list. `group_start[s]` (n + 1 entries) is where the
  // group of slot s starts. A margin lets bonded pairs be found while apart (in tension).
  // Distances are to the nearest image where `box` is periodic; throws InputError when a period is
  // shorter than three cells (2 Rmax + margin each), which the nearest-image search needs.
  // Pairs of two held particles (both_fixed) are left out unless `fixed_pairs`.
  void find_near_pairs(const Particles& p, const PeriodicBox& box, std::vector<FoundContact>& out, std::vector<int>& group_start,
                       double margin = 0, bool fixed_pairs = false);
  void find_near_pairs(const Particles& p, const PeriodicBox& box, std::vector<FoundContact>& out, double margin = 0) {
    std::vector<int> group_start;
    find_near_pairs(p, box, out, group_start, margin);
  }
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
  void bin(const Particles& p, const PeriodicBox& box, double margin);  // the grid and each cell's slots
  long cell_coord(double x, int d) const;           // any point: clamped to the grid
  long particle_cell_coord(double x, int d) const;  // a particle's: clamped inside the padding

  std::vector<int> cell_of_;     // per slot, its cell
  std::vector<int> cell_first_;  // per cell, where its slots start in cell_slots_ (+ the end)
  std::vector<int> cell_slots_;  // the slots cell by cell, in slot order within a cell
  Vec3 lo_ = Vec3::Zero();
  Vec3 edge_ = Vec3::Zero();  // per axis: a period is divided into whole cells
  double rmax_ = 0;
  long dims_[3] = {0, 0, 0};  // cells per axis, with the padding
  long pad_[3] = {0, 0, 0};   // per axis: 1 where it is not periodic (an empty cell at each end)
  std::vector<SearchPart> parts_;  // per thread, then joined
};

}  // namespace dem
