#include "forces/step_work.hpp"

#include <algorithm>

#include "simd/exact_sum.hpp"

namespace dem {

void add_particle_work(const Particles& p, const StepWorkInput& in, const BeforeMotion& before, long lo, long hi, StepWork& s) {
  const double dt = in.dt;
  const bool global_damping = in.global_damping();
  // A run of particles' terms first, without a branch, then each term's sum over the run in one
  // pass (add_all), in place of a FixedSum add per particle and term behind a test of its sums
  // (bench/results/design.md). A term that does not apply is +0, which changes no bit of a FixedSum.
  double fluid[kTermRun], prescribed[kTermRun], global[kTermRun];
  for (long first = lo; first < hi; first += kTermRun) {
    const long n = std::min(kTermRun, hi - first);
    for (long e = 0; e < n; ++e) {
      const long k = first + e, b = k - lo;
      const Vec3 v = Vec3(0.5 * (before.v[b] + p.v[k])), w = Vec3(0.5 * (before.w[b] + p.w[k]));
      // eq. P40: the fluid's force as the force loop took it (x^n, v^{n-1/2}).
      if (in.fluid) fluid[e] = in.fluid->force(p.radius[k], p.void_fraction[k], before.x[b], before.v[b], in.gravity).dot(v) * dt;
      const std::uint8_t fixed = in.any_fixed ? p.fixed[k] : 0;
      if (in.any_fixed)  // eq. P37
        prescribed[e] = fixed == kPrescribed ? -(in.force[k].v.dot(v) + in.torque[k].v.dot(w)) * dt : 0.0;
      if (global_damping)  // eq. P35: the integrator's m (v+ - v-) = F Δt - α m v̄ Δt takes α m |v̄|² Δt.
        global[e] = !fixed ? (in.alpha_r * p.mass[k] * v.squaredNorm() + in.alpha_theta * p.inertia(k) * w.squaredNorm()) * dt : 0.0;
    }
    if (in.fluid) add_all(s.fluid, fluid, n);
    if (in.any_fixed) add_all(s.prescribed, prescribed, n);
    if (global_damping) add_all(s.global, global, n);
  }
}

void WallWorkTerms::add_to(StepWork& sums) {
  add_all(sums.damping, damping.data(), static_cast<long>(damping.size()));
  add_all(sums.tangential, tangential.data(), static_cast<long>(tangential.size()));
  add_all(sums.walls, walls.data(), static_cast<long>(walls.size()));
  add_all(sums.rolling, rolling.data(), static_cast<long>(rolling.size()));
  damping.clear(), tangential.clear(), walls.clear(), rolling.clear();
}

}  // namespace dem
