#pragma once
// Periodic boundaries (a chute or a shear cell without side walls): along a periodic axis the
// domain [lo, hi) repeats with period L = hi - lo. A particle leaving at hi re-enters at lo, and its
// image count along that axis goes up by one, so that its unwrapped position x + image L (for
// displacements and the potential energy) is always known; pairs interact through the nearest
// image. Walls are not repeated: a wall meant to act everywhere must span the period.
#include <array>
#include <cmath>

#include "core/types.hpp"

namespace dem {

struct PeriodicBox {
  std::array<bool, 3> axis = {false, false, false};  // periodic along x, y, z
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();          // the period along the periodic axes [m]

  bool any() const { return axis[0] || axis[1] || axis[2]; }
  double length(int d) const { return hi[d] - lo[d]; }

  // The nearest image of a separation x_j - x_i of two positions inside the period (|d| < L,
  // give or take a step's drift): d - L round(d / L) with ties kept, as two comparisons instead of
  // a call to nearbyint (this is in the force loop). A pair that does not cross a boundary keeps
  // its bits.
  Vec3 nearest(Vec3 d) const {
    for (int a = 0; a < 3; ++a) {
      if (!axis[a]) continue;
      const double L = length(a);
      if (d[a] > 0.5 * L) d[a] -= L;
      else if (d[a] < -0.5 * L) d[a] += L;
    }
    return d;
  }

  // Brings x back into [lo, hi) along the periodic axes after a step (a particle moves far less
  // than a period per step: one shift suffices), counting the periods crossed in `image`.
  void wrap(Vec3& x, Vec3i& image) const {
    for (int a = 0; a < 3; ++a) {
      if (!axis[a]) continue;
      if (x[a] >= hi[a]) x[a] -= length(a), ++image[a];
      else if (x[a] < lo[a]) x[a] += length(a), --image[a];
    }
  }

  // The same for any position (a scene's initial state): as many periods as it takes.
  void wrap_far(Vec3& x, Vec3i& image) const {
    for (int a = 0; a < 3; ++a) {
      if (!axis[a]) continue;
      const double shift = std::floor((x[a] - lo[a]) / length(a));
      if (shift == 0) continue;
      x[a] -= shift * length(a);
      image[a] += static_cast<int>(shift);
      if (x[a] >= hi[a]) x[a] -= length(a), ++image[a];  // round-off at the upper end
    }
  }

  // The position as if no boundary had been crossed (x itself, to the bit, without periodic axes).
  Vec3 unwrapped(const Vec3& x, const Vec3i& image) const {
    Vec3 u = x;
    for (int a = 0; a < 3; ++a)
      if (axis[a]) u[a] += image[a] * length(a);
    return u;
  }

  bool operator==(const PeriodicBox& o) const {
    for (int a = 0; a < 3; ++a)
      if (axis[a] != o.axis[a] || (axis[a] && (lo[a] != o.lo[a] || hi[a] != o.hi[a]))) return false;
    return true;
  }
};

}  // namespace dem
