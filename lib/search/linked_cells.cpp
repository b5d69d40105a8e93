#include "search/linked_cells.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace dem {

namespace {
// Appends each thread's list to `out`, in thread order, and frees them: kept, they would double
// the memory of the found pairs at every rebuild.
void join_and_release(std::vector<std::vector<FoundContact>>& parts, std::vector<FoundContact>& out) {
  std::size_t n = out.size();
  for (const std::vector<FoundContact>& part : parts) n += part.size();
  out.reserve(n);
  for (std::vector<FoundContact>& part : parts) {
    out.insert(out.end(), part.begin(), part.end());
    std::vector<FoundContact>().swap(part);
  }
}
}  // namespace

long LinkedCells::cell_coord(double x, int d) const {
  return std::clamp(static_cast<long>(std::floor((x - lo_[d]) / edge_[d])), 0L, dims_[d] - 1);
}

void LinkedCells::bin(const Particles& p, const PeriodicBox& box, double margin) {
  const int n = static_cast<int>(p.size());
  Vec3 lo = n ? p.x[0] : Vec3::Zero(), hi = lo;
  double rmax = 0;
  for (int k = 0; k < n; ++k) {
    lo = lo.cwiseMin(p.x[k]);
    hi = hi.cwiseMax(p.x[k]);
    rmax = std::max(rmax, p.radius[k]);
  }
  // Cell edge >= 2 Rmax (+ margin) (eq. 3.1); widened if needed so the grid has at most ~2N + 27 cells,
  // which bounds memory when a particle flies far away. A period holds a whole number of cells.
  double edge = std::max(2 * rmax + margin, 1e-300);
  long* dims = dims_;
  for (;;) {
    long total = 1;
    for (int d = 0; d < 3; ++d) {
      if (box.axis[d]) {
        dims[d] = std::max(1L, static_cast<long>(std::floor(box.length(d) / edge)));
        lo_[d] = box.lo[d];
        edge_[d] = box.length(d) / dims[d];
      } else {
        dims[d] = std::max(1L, static_cast<long>(std::floor((hi[d] - lo[d]) / edge)) + 1);
        lo_[d] = lo[d];
        edge_[d] = edge;
      }
      total *= dims[d];
    }
    if (total <= 2L * n + 27) break;
    edge *= 1.26;
  }
  for (int d = 0; d < 3; ++d)
    if (box.axis[d] && dims[d] < 3) {
      std::ostringstream m;
      m << "periodic boundaries: the period along " << "xyz"[d] << " (" << box.length(d) << " m) must hold at least 3 search cells of "
        << 2 * rmax + margin << " m (the largest diameter plus the neighbour-list skin and bond reach): widen the period";
      throw InputError(m.str());
    }
  rmax_ = rmax;
  head_.assign(dims[0] * dims[1] * dims[2], -1);
  next_.resize(n);
  // Insert in reverse so each cell lists its particles in increasing slot order.
  for (int k = n - 1; k >= 0; --k) {
    const long c = (cell_coord(p.x[k][2], 2) * dims[1] + cell_coord(p.x[k][1], 1)) * dims[0] + cell_coord(p.x[k][0], 0);
    next_[k] = head_[c];
    head_[c] = k;
  }
}

void LinkedCells::find_near_pairs(const Particles& p, const PeriodicBox& box, std::vector<FoundContact>& out, double margin) {
  bin(p, box, margin);
  const long* dims = dims_;
  const long ncell = dims[0] * dims[1] * dims[2];
  const bool periodic = box.any();
  // Half of the neighbour shell: the 13 cells "after" the current one, plus the cell itself. With
  // at least 3 cells along a periodic axis, each pair of cells is still visited once.
  static constexpr int kHalf[13][3] = {{1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},   {-1, -1, 1},
                                       {0, -1, 1}, {1, -1, 1}, {-1, 0, 1}, {0, 0, 1},   {1, 0, 1},
                                       {-1, 1, 1}, {0, 1, 1},  {1, 1, 1}};
  // Cells are searched in parallel, each thread appending to its own list; the lists are joined
  // in thread order (callers that need an order independent of the thread count sort them).
  const int threads = omp_get_max_threads();
  per_thread_.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    std::vector<FoundContact>& mine = per_thread_[omp_get_thread_num()];
    mine.clear();
    auto test = [&](int a, int b) {
      if (p.both_fixed(a, b)) return;
      const double r = p.radius[a] + p.radius[b];
      const double d2 = (periodic ? box.nearest(p.x[a] - p.x[b]) : Vec3(p.x[a] - p.x[b])).squaredNorm();
      if (d2 < (r + margin) * (r + margin)) {
        if (p.id[a] < p.id[b]) mine.push_back({p.id[a], p.id[b], a, b});
        else mine.push_back({p.id[b], p.id[a], b, a});
      }
    };
    // A neighbour cell's coordinate along axis d, wrapped around a period; -1 when off the grid.
    auto along = [&](long c, int d) {
      if (c >= 0 && c < dims[d]) return c;
      return box.axis[d] ? (c + dims[d]) % dims[d] : -1L;
    };
#pragma omp for schedule(dynamic, 64)
    for (long c = 0; c < ncell; ++c) {
      const long cx = c % dims[0], cy = (c / dims[0]) % dims[1], cz = c / (dims[0] * dims[1]);
      for (int a = head_[c]; a >= 0; a = next_[a]) {
        for (int b = next_[a]; b >= 0; b = next_[b]) test(a, b);
        for (const auto& o : kHalf) {
          const long x = along(cx + o[0], 0), y = along(cy + o[1], 1), z = along(cz + o[2], 2);
          if (x < 0 || y < 0 || z < 0) continue;
          for (int b = head_[(z * dims[1] + y) * dims[0] + x]; b >= 0; b = next_[b]) test(a, b);
        }
      }
    }
  }
  join_and_release(per_thread_, out);
}

void LinkedCells::find_near_walls(const Particles& p, const std::vector<WallGeometry>& walls, std::vector<FoundContact>& out,
                                  double margin) {
  if (p.size() == 0) return;
  const int threads = omp_get_max_threads();
  per_thread_.resize(threads);
  const long nw = static_cast<long>(walls.size());
  const double grow = rmax_ + margin;
#pragma omp parallel num_threads(threads)
  {
    std::vector<FoundContact>& mine = per_thread_[omp_get_thread_num()];
    mine.clear();
    // One element at a time: a box has six walls, each covering thousands of cells.
#pragma omp for schedule(dynamic, 1)
    for (long w = 0; w < nw; ++w) {
      const WallGeometry& g = walls[w];
      Vec3 blo = g.vertices[0], bhi = g.vertices[0];
      for (int v = 1; v < g.count; ++v) blo = blo.cwiseMin(g.vertices[v]), bhi = bhi.cwiseMax(g.vertices[v]);
      blo.array() -= grow;
      bhi.array() += grow;
      long c0[3], c1[3];
      bool outside = false;
      for (int d = 0; d < 3; ++d) {
        // Cells past the grid's last one hold nothing beyond it: an element far away is skipped.
        outside = outside || bhi[d] < lo_[d] || blo[d] > lo_[d] + dims_[d] * edge_[d];
        c0[d] = cell_coord(blo[d], d);
        c1[d] = cell_coord(bhi[d], d);
      }
      if (outside) continue;
      for (long z = c0[2]; z <= c1[2]; ++z)
        for (long y = c0[1]; y <= c1[1]; ++y)
          for (long x = c0[0]; x <= c1[0]; ++x)
            for (int k = head_[(z * dims_[1] + y) * dims_[0] + x]; k >= 0; k = next_[k]) {
              const double reach = p.radius[k] + margin;
              if ((closest_point(g, p.x[k]) - p.x[k]).squaredNorm() < reach * reach)
                mine.push_back({p.id[k], static_cast<Index>(w), k, static_cast<int>(w)});
            }
    }
  }
  join_and_release(per_thread_, out);
}

}  // namespace dem
