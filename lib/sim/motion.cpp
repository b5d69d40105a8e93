#include "sim/motion.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "simd/simd.hpp"

namespace dem {

namespace {

// One test per coordinate, no branch (Eigen's allFinite on each vector cost 7 % of a settle's time).
inline bool finite_state(const MotionArrays& a, long i) {
  const Vec3 s = (a.x[i] + a.v[i]) + a.w[i];
  return (std::abs(s.x()) <= DBL_MAX) & (std::abs(s.y()) <= DBL_MAX) & (std::abs(s.z()) <= DBL_MAX);
}

// Particle i: held, it stops; free, it moves under its net load (eq. 2.31-2.34). False where its
// new state is not finite.
inline bool move_one(const MotionArrays& a, const MotionConstants& c, long i) {
  if (a.fixed && a.fixed[i]) {
    a.v[i] = a.w[i] = Vec3::Zero();
    return true;
  }
  a.v[i] = (c.ar * a.v[i] + a.force[i].v * (c.dt / a.mass[i])) * c.br;
  a.w[i] = (c.at * a.w[i] + a.torque[i].v * (c.dt / sphere_inertia(a.mass[i], a.radius[i]))) * c.bt;
  a.x[i] += a.v[i] * c.dt;
  if (c.box.any()) c.box.wrap(a.x[i], a.image[i]);
  return finite_state(a, i);
}

long move_one_by_one(const MotionArrays& a, const MotionConstants& c, long first, long last) {
  long bad = -1;
  for (long i = first; i < last; ++i)
    if (!move_one(a, c, i)) bad = i;
  return bad;
}

#ifdef DEM_SIMD_LOOPS
using simd::by_axis;
using simd::by_particle;

// Four particles' padded loads [x y z -] as their vectors are laid out (simd/simd.hpp): [x0 y0 z0 x1],
// [y1 z1 x2 y2], [z2 x3 y3 z3]. From loads, broadcasts and blends only (no shuffle across the
// register's halves: those have one port, which the integration keeps busy already).
[[gnu::target("avx2")]] inline void packed_loads(const LoadSum* s, __m256d out[3]) {
  const double* f = s[0].v.data();  // 16 doubles: x y z - of each
  out[0] = _mm256_blend_pd(_mm256_load_pd(f), _mm256_broadcast_sd(f + 4), 0b1000);  // [x0 y0 z0 -] with x1
  out[1] = _mm256_blend_pd(_mm256_loadu_pd(f + 5), _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(f + 8)), 0b1100);  // [y1 z1 - x2] with x2 y2
  out[2] = _mm256_blend_pd(_mm256_loadu_pd(f + 11), _mm256_broadcast_sd(f + 10), 0b0001);  // [- x3 y3 z3] with z2
}

[[gnu::target("avx2")]] long move_four_at_a_time(const MotionArrays& a, const MotionConstants& c, long first, long last) {
  const __m256d ar = _mm256_set1_pd(c.ar), br = _mm256_set1_pd(c.br), at = _mm256_set1_pd(c.at), bt = _mm256_set1_pd(c.bt);
  const __m256d dt = _mm256_set1_pd(c.dt), two_fifths = _mm256_set1_pd(0.4), largest = _mm256_set1_pd(DBL_MAX);
  const __m256d sign = _mm256_set1_pd(-0.0);
  // Four particles' vectors in three registers (simd/simd.hpp), and what they are compared with:
  // the period (an axis that is not periodic: no bound), to see which particles left it.
  __m256d period_lo[3], period_hi[3];
  Vec3 lo, hi;
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis] = c.box.axis[axis] ? c.box.lo[axis] : -std::numeric_limits<double>::infinity();
    hi[axis] = c.box.axis[axis] ? c.box.hi[axis] : std::numeric_limits<double>::infinity();
  }
  by_axis(lo, period_lo), by_axis(hi, period_hi);
  long bad = -1;
  long i = first;
  for (; i + 4 <= last; i += 4) {
    if (a.fixed) {
      std::uint32_t held;
      std::memcpy(&held, a.fixed + i, 4);
      if (held) {  // one by one
        bad = std::max(bad, move_one_by_one(a, c, i, i + 4));
        continue;
      }
    }
    double* const x = a.x[i].data();
    double* const v = a.v[i].data();
    double* const w = a.w[i].data();
    const __m256d m = _mm256_loadu_pd(a.mass + i), r = _mm256_loadu_pd(a.radius + i);
    __m256d to_v[3], to_w[3], force[3], torque[3];
    by_particle(dt / m, to_v);                             // dt / m
    by_particle(dt / (((two_fifths * m) * r) * r), to_w);  // dt / I, I = sphere_inertia(m, a)
    packed_loads(a.force + i, force), packed_loads(a.torque + i, torque);
    int broken = 0, left = 0;
    for (int q = 0; q < 3; ++q) {
      const __m256d vq = (ar * _mm256_loadu_pd(v + 4 * q) + force[q] * to_v[q]) * br;
      const __m256d wq = (at * _mm256_loadu_pd(w + 4 * q) + torque[q] * to_w[q]) * bt;
      const __m256d xq = _mm256_loadu_pd(x + 4 * q) + vq * dt;
      _mm256_storeu_pd(v + 4 * q, vq), _mm256_storeu_pd(w + 4 * q, wq), _mm256_storeu_pd(x + 4 * q, xq);
      // finite_state: |x + v + w| is NaN or above the largest double somewhere.
      const __m256d sum = _mm256_andnot_pd(sign, (xq + vq) + wq);
      broken |= _mm256_movemask_pd(_mm256_cmp_pd(sum, largest, _CMP_NLE_UQ));
      left |= _mm256_movemask_pd(_mm256_or_pd(_mm256_cmp_pd(xq, period_hi[q], _CMP_GE_OQ), _mm256_cmp_pd(xq, period_lo[q], _CMP_LT_OQ)));
    }
    if (left)  // PeriodicBox::wrap, which leaves the others as they are
      for (long k = i; k < i + 4; ++k) c.box.wrap(a.x[k], a.image[k]);
    if (broken)  // which one
      for (long k = i; k < i + 4; ++k)
        if (!finite_state(a, k)) bad = k;
  }
  return std::max(bad, move_one_by_one(a, c, i, last));
}
#endif

}  // namespace

long move_particles(const MotionArrays& a, const MotionConstants& c, long first, long last) {
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) return move_four_at_a_time(a, c, first, last);
#endif
  return move_one_by_one(a, c, first, last);
}

}  // namespace dem
