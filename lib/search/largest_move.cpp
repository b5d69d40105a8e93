#include "search/largest_move.hpp"

#include <algorithm>
#include <limits>

#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

double one_by_one(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
  double largest = 0;
  const bool periodic = box.any();
  for (long k = first; k < last; ++k) {
    const Vec3 moved = x[k] - x_build[k];
    const Vec3 d = periodic ? box.nearest(moved) : moved;
    largest = std::max(largest, (d.x() * d.x() + d.y() * d.y()) + d.z() * d.z());
  }
  return largest;
}

#ifdef DEM_SIMD_LOOPS
// Four particles' positions in three registers (simd/layout.hpp: packed).
DEM_AVX2 double four_at_a_time(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
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
  long k = first;
  for (; k + 4 <= last; k += 4) {
    Lanes4 s[3];  // squared coordinates of the displacements
    for (int q = 0; q < 3; ++q) {
      const Lanes4 moved = simd::load(x[k].data() + 4 * q) - simd::load(x_build[k].data() + 4 * q);
      const Lanes4 d = simd::nearest_image(moved, L[q], half_L[q]);
      s[q] = d * d;
    }
    const lanes::Triple<Lanes4> per_axis = simd::unpack(s);  // dx0^2 dx1^2 dx2^2 dx3^2, and so on
    largest = simd::max(largest, (per_axis.x + per_axis.y) + per_axis.z);
  }
  alignas(32) double lanes[4];
  simd::store_aligned(lanes, largest);
  return std::max({lanes[0], lanes[1], lanes[2], lanes[3], one_by_one(x, x_build, box, k, last)});
}
#endif

}  // namespace

double largest_move2(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last) {
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) return four_at_a_time(x, x_build, box, first, last);
#endif
  return one_by_one(x, x_build, box, first, last);
}

}  // namespace dem
