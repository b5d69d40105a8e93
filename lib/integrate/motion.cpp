#include "integrate/motion.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "simd/exact_sum.hpp"
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

// Where the contacts' work of a run of particles is written before it is summed (MotionWork): the
// run's terms first, each term's sum over the run in one pass (add_all), as the ledger's other
// particle terms (forces/step_work.cpp).
struct RunTerms {
  double damping[kTermRun], tangential[kTermRun], rolling[kTermRun];
};

// Particle i: held, it stops; prescribed, it moves on at its own v and w, whatever its load; free,
// it moves under its net load (eq. 2.31-2.34). False where its new state is not finite. With
// `work`, its contacts' work into entry e of `terms` (its sums at work->contacts entry s).
template <bool Work>
inline bool move_one(const MotionArrays& a, const MotionConstants& c, long i, const MotionWork* work, long s, RunTerms* terms, long e) {
  const Vec3 v_before = a.v[i], w_before = a.w[i];
  const std::uint8_t fixed = a.fixed ? a.fixed[i] : 0;
  const bool held = fixed && fixed != kPrescribed;
  if (held) {
    a.v[i] = a.w[i] = Vec3::Zero();
  } else if (!fixed) {
    a.v[i] = next_velocity(c.ar, a.v[i], a.force[i].v, c.dt / a.mass[i], c.br);
    a.w[i] = next_velocity(c.at, a.w[i], a.torque[i].v, c.dt / sphere_inertia(a.mass[i], a.radius[i]), c.bt);
  }
  if constexpr (Work) {
    const ParticleWork& q = work->contacts;
    const Vec3 v = Vec3(0.5 * (v_before + a.v[i])), w = Vec3(0.5 * (w_before + a.w[i]));  // v̄, w̄
    // Eigen's dot of three is (x x' + y y') + z z', as the four-wide loop's.
    const ContactWorkTerms<double> t = contact_work_terms(q.damping[s].v.dot(v), q.tangential[s].v.dot(v), q.torque_per_radius[s].v.dot(w),
                                                         work->couples ? q.couple[s].v.dot(w) : 0.0, a.radius[i], c.dt);
    terms->damping[e] = t.damping, terms->tangential[e] = t.tangential, terms->rolling[e] = t.rolling;
  }
  if (held) return true;  // stays where it is
  a.x[i] += a.v[i] * c.dt;
  if (c.box.any()) c.box.wrap(a.x[i], a.image[i]);
  return finite_state(a, i);
}

// Particles [first, last), with their contacts' terms from entry e0 of `terms` on.
template <bool Work>
long move_one_by_one(const MotionArrays& a, const MotionConstants& c, long first, long last, const MotionWork* work, long s0,
                     RunTerms* terms, long e0) {
  long bad = -1;
  for (long i = first; i < last; ++i)
    if (!move_one<Work>(a, c, i, work, s0 + (i - first), terms, e0 + (i - first))) bad = i;
  return bad;
}

#ifdef DEM_SIMD_LOOPS
using lanes::Lanes4;

// Particles [first, last), with their contacts' work (Work) from their sums at work->contacts entry
// s0 on into `terms` from entry 0 on.
template <bool Work>
DEM_AVX2 long move_four_at_a_time(const MotionArrays& a, const MotionConstants& c, long first, long last, const MotionWork* work, long s0,
                                  RunTerms* terms) {
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
        bad = std::max(bad, move_one_by_one<Work>(a, c, i, i + 4, work, s0 + (i - first), terms, i - first));
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
    Lanes4 v_mean[3], w_mean[3];  // v̄, w̄ packed (MotionWork)
    for (int q = 0; q < 3; ++q) {
      const Lanes4 v_before = simd::load(v + 4 * q), w_before = simd::load(w + 4 * q);
      const Lanes4 vq = next_velocity(ar, v_before, force[q], to_v[q], br);
      const Lanes4 wq = next_velocity(at, w_before, torque[q], to_w[q], bt);
      if constexpr (Work) v_mean[q] = broadcast(0.5) * (v_before + vq), w_mean[q] = broadcast(0.5) * (w_before + wq);
      const Lanes4 xq = simd::load(x + 4 * q) + vq * dt;
      simd::store(v + 4 * q, vq), simd::store(w + 4 * q, wq), simd::store(x + 4 * q, xq);
      // finite_state: |x + v + w| is NaN or above the largest double somewhere.
      broken |= simd::bits(simd::not_less_or_equal(simd::abs((xq + vq) + wq), largest));
      left |= simd::bits(simd::either(simd::greater_or_equal(xq, period_hi[q]), lanes::less(xq, period_lo[q])));
    }
    if constexpr (Work) {
      const long s = s0 + (i - first), e = i - first;
      const ParticleWork& q = work->contacts;
      // Four particles' sums (padded, as their loads) times their mean velocities, packed; each
      // particle's three products then summed (x x' + y y') + z z', as the plain loop's.
      const auto dot = [&](const LoadSum* sums, const Lanes4 (&mean)[3]) DEM_AVX2_LAMBDA {
        Lanes4 f[3];
        simd::pack_padded(sums[s].v.data(), f);
        const Lanes4 products[3] = {f[0] * mean[0], f[1] * mean[1], f[2] * mean[2]};
        const lanes::Triple<Lanes4> p = simd::unpack(products);
        return (p.x + p.y) + p.z;
      };
      const ContactWorkTerms<Lanes4> t = contact_work_terms(dot(q.damping, v_mean), dot(q.tangential, v_mean), dot(q.torque_per_radius, w_mean),
                                                            work->couples ? dot(q.couple, w_mean) : Lanes4(0.0), r, dt);
      simd::store(terms->damping + e, t.damping), simd::store(terms->tangential + e, t.tangential), simd::store(terms->rolling + e, t.rolling);
    }
    if (left)  // PeriodicBox::wrap, which leaves the others as they are
      for (long k = i; k < i + 4; ++k) c.box.wrap(a.x[k], a.image[k]);
    if (broken)  // which one
      for (long k = i; k < i + 4; ++k)
        if (!finite_state(a, k)) bad = k;
  }
  return std::max(bad, move_one_by_one<Work>(a, c, i, last, work, s0 + (i - first), terms, i - first));
}
#endif

// Particles [first, last) (at most kTermRun with Work), their contacts' work into `terms` from entry 0.
template <bool Work>
long move_run(const MotionArrays& a, const MotionConstants& c, long first, long last, const MotionWork* work, long s0, RunTerms* terms) {
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) return move_four_at_a_time<Work>(a, c, first, last, work, s0, terms);
#endif
  return move_one_by_one<Work>(a, c, first, last, work, s0, terms, 0);
}

}  // namespace

long move_particles(const MotionArrays& a, const MotionConstants& c, long first, long last, const MotionWork* work) {
  if (a.before_x) {
    copy_vectors(a.x + first, last - first, a.before_x + first);
    copy_vectors(a.v + first, last - first, a.before_v + first);
    copy_vectors(a.w + first, last - first, a.before_w + first);
  }
  if (!work) return move_run<false>(a, c, first, last, nullptr, 0, nullptr);
  long bad = -1;
  RunTerms terms;
  for (long lo = first; lo < last; lo += kTermRun) {
    const long hi = std::min(last, lo + kTermRun), n = hi - lo;
    bad = std::max(bad, move_run<true>(a, c, lo, hi, work, lo - first, &terms));
    add_all(work->sums->damping, terms.damping, n);
    add_all(work->sums->tangential, terms.tangential, n);
    if (work->couples) add_all(work->sums->rolling, terms.rolling, n);
  }
  return bad;
}

}  // namespace dem
