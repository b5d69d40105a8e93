#include "search/neighbour_list.hpp"

#include <algorithm>
#include <parallel/algorithm>
#include <cmath>
#include <cstring>

#include <omp.h>

#include "core/keep_items.hpp"
#include "search/largest_move.hpp"

namespace dem {

bool NeighbourList::needs_rebuild(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin,
                                  double skin) const {
  if (!valid_ || margin != margin_build_ || skin != skin_build_ || !(box == box_build_) || p.size() != x_build_.size() ||
      4 * walls.size() != wall_build_.size())
    return true;
  // Two particles approach by at most Moves::approach() (twice the largest displacement, or less
  // where they moved together), a particle and a wall by the particle's displacement plus the
  // wall's (a planar polygon moves no further than its vertices), where there are walls. Across a
  // periodic boundary the displacement is the nearest image's.
  Moves moved;
  int changed = 0;  // ids or fixed flags
  const long n = static_cast<long>(p.size());
#pragma omp parallel reduction(| : changed)
  {
    const long threads = omp_get_num_threads(), t = omp_get_thread_num();
    const long first = n * t / threads, last = n * (t + 1) / threads;
    const Moves mine = moves_since(p.x.data(), x_build_.data(), box, first, last);
#pragma omp critical(dem_moves)
    moved.add(mine);  // smallest and largest values: the same for any order
    changed = last > first && (std::memcmp(p.id.data() + first, id_build_.data() + first, (last - first) * sizeof(Index)) != 0 ||
                               std::memcmp(p.fixed.data() + first, fixed_build_.data() + first, last - first) != 0);
  }
  if (changed) return true;
  const double dp = std::sqrt(moved.largest2);
  double dw2 = 0;
  const long nw = static_cast<long>(walls.size());
#pragma omp parallel for schedule(static) reduction(max : dw2) if (nw > 1000)
  for (long w = 0; w < nw; ++w)
    for (int v = 0; v < walls[w].count; ++v) dw2 = std::max(dw2, (walls[w].vertices[v] - wall_build_[4 * w + v]).squaredNorm());
  const double dw = std::sqrt(dw2);
  return moved.approach() > skin || (nw > 0 && dp + dw > skin);
}

void NeighbourList::keep_only(const Kept& keep) {
  keep_items(x_build_, keep), keep_items(id_build_, keep), keep_items(fixed_build_, keep);
}

void NeighbourList::build(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin,
                          double skin) {
  cells_.find_near_pairs(p, box, pairs_, pair_groups_, margin + skin);

  wall_pairs_.clear();
  cells_.find_near_walls(p, walls, wall_pairs_, margin + skin);
  __gnu_parallel::sort(wall_pairs_.begin(), wall_pairs_.end());

  x_build_ = p.x;
  id_build_ = p.id;
  fixed_build_ = p.fixed;
  wall_build_.assign(4 * walls.size(), Vec3::Zero());
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (int v = 0; v < walls[w].count; ++v) wall_build_[4 * w + v] = walls[w].vertices[v];
  margin_build_ = margin;
  skin_build_ = skin;
  box_build_ = box;
  valid_ = true;
  ++builds_;
}

void NeighbourList::sort_pairs_by_key() {
  __gnu_parallel::sort(pairs_.begin(), pairs_.end());  // keys are unique: the same order for any thread count
}

bool NeighbourList::update(const Particles& p, const PeriodicBox& box, const std::vector<WallGeometry>& walls, double margin,
                           double skin) {
  const bool automatic = !(skin > 0);
  if (!needs_rebuild(p, box, walls, margin, automatic ? skin_build_ : skin)) return false;
  build(p, box, walls, margin, automatic ? automatic_skin(p) : skin);
  return true;
}

double NeighbourList::automatic_skin(const Particles& p) {
  double sum = 0;
  for (double a : p.radius) sum += a;
  return p.size() ? 0.2 * sum / p.size() : 0.0;
}

}  // namespace dem
