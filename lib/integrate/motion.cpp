#include "integrate/motion.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

namespace {

// One test per coordinate, no branch: Eigen's allFinite per vector was costly (bench/results/design.md).
inline bool finite_state(const MotionArrays& a, long i) {
  const Vec3 s = (a.x[i] + a.v[i]) + a.w[i];
  return (int(std::abs(s.x()) <= DBL_MAX) & int(std::abs(s.y()) <= DBL_MAX) & int(std::abs(s.z()) <= DBL_MAX)) != 0;
}

// Particle i: held, it stops; prescribed, it moves on at its own v and w, whatever its load; free,
// it moves under its net load (eq. 2.31-2.34). False where its new state is not finite.
inline bool move_one(const MotionArrays& a, const MotionConstants& c, long i) {
  if (a.fixed && a.fixed[i]) {
    if (a.fixed[i] != kPrescribed) {
      a.v[i] = a.w[i] = Vec3::Zero();
      return true;
    }
  } else {
    a.v[i] = next_velocity(c.ar, a.v[i], a.force[i].v, c.dt / a.mass[i], c.br);
    a.w[i] = next_velocity(c.at, a.w[i], a.torque[i].v, c.dt / sphere_inertia(a.mass[i], a.radius[i]), c.bt);
  }
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
using lanes::Lanes4;

DEM_AVX2 long move_four_at_a_time(const MotionArrays& a, const MotionConstants& c, long first, long last) {
  using simd::broadcast;
  const Lanes4 ar = broadcast(c.ar), br = broadcast(c.br), at = broadcast(c.at), bt = broadcast(c.bt);
  const Lanes4 dt = broadcast(c.dt), largest = broadcast(DBL_MAX);
  // Four particles' vectors in three registers (simd/layout.hpp: packed), and what they are
  // compared with: the period (an axis that is not periodic: no bound), to see which particles
  // left it.
  Lanes4 period_lo[3], period_hi[3];
  Vec3 lo, hi;
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis] = c.box.axis[axis] ? c.box.lo[axis] : -std::numeric_limits<double>::infinity();
    hi[axis] = c.box.axis[axis] ? c.box.hi[axis] : std::numeric_limits<double>::infinity();
  }
  simd::by_axis(lo, period_lo), simd::by_axis(hi, period_hi);
  long bad = -1;
  long i = first;
  for (; i + 4 <= last; i += 4) {
    if (a.fixed) {
      std::uint32_t fixed;
      std::memcpy(&fixed, a.fixed + i, 4);
      if (fixed) {  // one by one
        bad = std::max(bad, move_one_by_one(a, c, i, i + 4));
        continue;
      }
    }
    double* const x = a.x[i].data();
    double* const v = a.v[i].data();
    double* const w = a.w[i].data();
    const Lanes4 m = simd::load(a.mass + i), r = simd::load(a.radius + i);
    Lanes4 to_v[3], to_w[3], force[3], torque[3];
    simd::by_particle(dt / m, to_v);                             // dt / m
    simd::by_particle(dt / sphere_inertia(m, r), to_w);          // dt / I
    // Four particles' padded loads [x y z -] (state/load_sum.hpp), packed as their vectors are.
    simd::pack_padded(a.force[i].v.data(), force), simd::pack_padded(a.torque[i].v.data(), torque);
    int broken = 0, left = 0;
    for (int q = 0; q < 3; ++q) {
      const Lanes4 vq = next_velocity(ar, simd::load(v + 4 * q), force[q], to_v[q], br);
      const Lanes4 wq = next_velocity(at, simd::load(w + 4 * q), torque[q], to_w[q], bt);
      const Lanes4 xq = simd::load(x + 4 * q) + vq * dt;
      simd::store(v + 4 * q, vq), simd::store(w + 4 * q, wq), simd::store(x + 4 * q, xq);
      // finite_state: |x + v + w| is NaN or above the largest double somewhere.
      broken |= simd::bits(simd::not_less_or_equal(simd::abs((xq + vq) + wq), largest));
      left |= simd::bits(simd::either(simd::greater_or_equal(xq, period_hi[q]), lanes::less(xq, period_lo[q])));
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
  if (a.before_x) {
    copy_vectors(a.x + first, last - first, a.before_x + first);
    copy_vectors(a.v + first, last - first, a.before_v + first);
    copy_vectors(a.w + first, last - first, a.before_w + first);
  }
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) return move_four_at_a_time(a, c, first, last);
#endif
  return move_one_by_one(a, c, first, last);
}

}  // namespace dem
