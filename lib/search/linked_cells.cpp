#include "search/linked_cells.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

void LinkedCells::find_near_pairs(const Particles& p, std::vector<FoundContact>& out, double margin) {
  const int n = static_cast<int>(p.size());
  if (n < 2) return;
  Vec3 lo = p.x[0], hi = p.x[0];
  double rmax = 0;
  for (int k = 0; k < n; ++k) {
    lo = lo.cwiseMin(p.x[k]);
    hi = hi.cwiseMax(p.x[k]);
    rmax = std::max(rmax, p.radius[k]);
  }
  // Cell edge >= 2 Rmax (+ margin) (eq. 3.1); widened if needed so the grid has at most ~2N + 27 cells,
  // which bounds memory when a particle flies far away.
  double edge = 2 * rmax + margin;
  const Vec3 span = hi - lo;
  long dims[3];
  for (;;) {
    long total = 1;
    for (int d = 0; d < 3; ++d) {
      dims[d] = std::max(1L, static_cast<long>(std::floor(span[d] / edge)) + 1);
      total *= dims[d];
    }
    if (total <= 2L * n + 27) break;
    edge *= 1.26;
  }
  const long ncell = dims[0] * dims[1] * dims[2];
  head_.assign(ncell, -1);
  next_.resize(n);
  auto cell_coord = [&](const Vec3& x, int d) {
    return std::min(dims[d] - 1, static_cast<long>((x[d] - lo[d]) / edge));
  };
  // Insert in reverse so each cell lists its particles in increasing slot order.
  for (int k = n - 1; k >= 0; --k) {
    const long c = (cell_coord(p.x[k], 2) * dims[1] + cell_coord(p.x[k], 1)) * dims[0] + cell_coord(p.x[k], 0);
    next_[k] = head_[c];
    head_[c] = k;
  }
  // Half of the neighbour shell: the 13 cells "after" the current one, plus the cell itself.
  static constexpr int kHalf[13][3] = {{1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},   {-1, -1, 1},
                                       {0, -1, 1}, {1, -1, 1}, {-1, 0, 1}, {0, 0, 1},   {1, 0, 1},
                                       {-1, 1, 1}, {0, 1, 1},  {1, 1, 1}};
  auto test = [&](int a, int b) {
    const double r = p.radius[a] + p.radius[b];
    const double d2 = (p.x[a] - p.x[b]).squaredNorm();
    if (d2 < (r + margin) * (r + margin)) {
      if (p.id[a] < p.id[b]) out.push_back({p.id[a], p.id[b], a, b});
      else out.push_back({p.id[b], p.id[a], b, a});
    }
  };
  for (long cz = 0; cz < dims[2]; ++cz)
    for (long cy = 0; cy < dims[1]; ++cy)
      for (long cx = 0; cx < dims[0]; ++cx) {
        const long c = (cz * dims[1] + cy) * dims[0] + cx;
        for (int a = head_[c]; a >= 0; a = next_[a]) {
          for (int b = next_[a]; b >= 0; b = next_[b]) test(a, b);
          for (const auto& o : kHalf) {
            const long x = cx + o[0], y = cy + o[1], z = cz + o[2];
            if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
            for (int b = head_[(z * dims[1] + y) * dims[0] + x]; b >= 0; b = next_[b]) test(a, b);
          }
        }
      }
}

}  // namespace dem
