#pragma once
// The spheres placed so far in a hash grid of cells one largest diameter wide: O(1) overlap checks
// for generation (fill.cpp) and insertion (insertion.cpp), which both place spheres one at a time.
#include <cmath>
#include <unordered_map>
#include <vector>

#include "state/particles.hpp"

namespace dem {

class SphereGrid {
 public:
  // cell: at least the largest diameter among the spheres added and the candidates asked about.
  SphereGrid(const Particles& p, double cell) : p_(p), cell_(cell) {}

  void add(int slot) { grid_[key(cell(p_.x[slot][0]), cell(p_.x[slot][1]), cell(p_.x[slot][2]))].push_back(slot); }

  // True when a sphere of radius a centred at x overlaps none of the spheres added.
  bool free_at(const Vec3& x, double a) const {
    const long ci = cell(x[0]), cj = cell(x[1]), ck = cell(x[2]);
    for (long di = -1; di <= 1; ++di)
      for (long dj = -1; dj <= 1; ++dj)
        for (long dk = -1; dk <= 1; ++dk) {
          auto it = grid_.find(key(ci + di, cj + dj, ck + dk));
          if (it == grid_.end()) continue;
          for (int o : it->second) {
            const double r = a + p_.radius[o];
            if ((p_.x[o] - x).squaredNorm() < r * r) return false;
          }
        }
    return true;
  }

 private:
  long cell(double c) const { return static_cast<long>(std::floor(c / cell_)); }
  static long key(long i, long j, long k) { return (i * 73856093L) ^ (j * 19349663L) ^ (k * 83492791L); }

  const Particles& p_;
  double cell_;
  std::unordered_map<long, std::vector<int>> grid_;
};

}  // namespace dem
