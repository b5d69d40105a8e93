#include "search/largest_move.hpp"

#include <algorithm>
#include <limits>

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
// Four particles' positions in three registers (simd/simd.hpp).
[[gnu::target("avx2")]] double four_at_a_time(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first,
                                              long last) {
  // The period and its half along each register lane's axis (simd::nearest_image: an axis that is
  // not periodic has L = 0 and L/2 = infinity).
  Vec3 length, half;
  for (int axis = 0; axis < 3; ++axis) {
    length[axis] = box.axis[axis] ? box.length(axis) : 0.0;
    half[axis] = box.axis[axis] ? 0.5 * box.length(axis) : std::numeric_limits<double>::infinity();
  }
  __m256d L[3], half_L[3];
  simd::by_axis(length, L), simd::by_axis(half, half_L);
  __m256d largest = _mm256_setzero_pd();
  long k = first;
  for (; k + 4 <= last; k += 4) {
    __m256d s[3];  // squared coordinates of the displacements
    for (int q = 0; q < 3; ++q) {
      const __m256d moved = _mm256_loadu_pd(x[k].data() + 4 * q) - _mm256_loadu_pd(x_build[k].data() + 4 * q);
      const __m256d d = simd::nearest_image(moved, L[q], half_L[q]);
      s[q] = d * d;
    }
    // Per particle: [dx0 dx1 dx2 dx3]^2 and so on, gathered from the three registers.
    const __m256d a = s[0], b = s[1], c = s[2];
    const __m256d sx = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0100), c, 0b0010), 0b01101100);
    const __m256d sy = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b1001), c, 0b0100), 0b10110001);
    const __m256d sz = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0010), c, 0b1001), 0b11000110);
    largest = _mm256_max_pd(largest, (sx + sy) + sz);
  }
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, largest);
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
