#include "search/largest_move.hpp"

#include <algorithm>
#include <limits>

#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

Moves one_by_one(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
  Moves m;
  const bool periodic = box.any();
  for (long k = first; k < last; ++k) {
    const Vec3 moved = x[k] - x_build[k];
    const Vec3 d = periodic ? box.nearest(moved) : moved;
    m.largest2 = std::max(m.largest2, (d.x() * d.x() + d.y() * d.y()) + d.z() * d.z());
    m.lo = m.lo.cwiseMin(d), m.hi = m.hi.cwiseMax(d);
  }
  return m;
}

#ifdef DEM_SIMD_LOOPS
// Four particles' positions in three registers (simd/layout.hpp: packed). Periodic: through the
// nearest image (without periodic boundaries the displacement is the difference itself, and the
// image's seven operations per register were over half of the loop's).
template <bool Periodic>
DEM_AVX2 Moves four_at_a_time(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
  using lanes::Lanes4;
  // The period and its half along each register lane's axis (simd::nearest_image: an axis that is
  // not periodic has L = 0 and L/2 = infinity).
  Vec3 length, half;
  for (int axis = 0; axis < 3; ++axis) {
    length[axis] = box.axis[axis] ? box.length(axis) : 0.0;
    half[axis] = box.axis[axis] ? 0.5 * box.length(axis) : std::numeric_limits<double>::infinity();
  }
  Lanes4 L[3], half_L[3];
  simd::by_axis(length, L), simd::by_axis(half, half_L);
  Lanes4 largest{};  // +0 in every lane
  // The smallest and largest coordinates per register lane: register q's lane l holds axis (4q + l) % 3.
  Lanes4 lo[3], hi[3];
  for (int q = 0; q < 3; ++q) lo[q] = simd::broadcast(std::numeric_limits<double>::infinity()), hi[q] = -lo[q];
  long k = first;
  for (; k + 4 <= last; k += 4) {
    Lanes4 s[3];  // squared coordinates of the displacements
    for (int q = 0; q < 3; ++q) {
      const Lanes4 moved = simd::load(x[k].data() + 4 * q) - simd::load(x_build[k].data() + 4 * q);
      const Lanes4 d = Periodic ? simd::nearest_image(moved, L[q], half_L[q]) : moved;
      s[q] = d * d;
      lo[q] = simd::min(lo[q], d), hi[q] = simd::max(hi[q], d);
    }
    const lanes::Triple<Lanes4> per_axis = simd::unpack(s);  // dx0^2 dx1^2 dx2^2 dx3^2, and so on
    largest = simd::max(largest, (per_axis.x + per_axis.y) + per_axis.z);
  }
  Moves m = one_by_one(x, x_build, box, k, last);
  alignas(32) double lanes[4], low[4], high[4];
  simd::store_aligned(lanes, largest);
  m.largest2 = std::max({lanes[0], lanes[1], lanes[2], lanes[3], m.largest2});
  for (int q = 0; q < 3; ++q) {
    simd::store_aligned(low, lo[q]), simd::store_aligned(high, hi[q]);
    for (int l = 0; l < 4; ++l) {
      const int axis = (4 * q + l) % 3;
      m.lo[axis] = std::min(m.lo[axis], low[l]), m.hi[axis] = std::max(m.hi[axis], high[l]);
    }
  }
  return m;
}
#endif

}  // namespace

Moves moves_since(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on())
    return box.any() ? four_at_a_time<true>(x, x_build, box, first, last) : four_at_a_time<false>(x, x_build, box, first, last);
#endif
  return one_by_one(x, x_build, box, first, last);
}

}  // namespace dem
