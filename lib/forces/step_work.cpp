#include "forces/step_work.hpp"

namespace dem {

void add_particle_work(const Particles& p, const StepWorkInput& in, const BeforeMotion& before, long lo, long hi, StepWork& s) {
  const double dt = in.dt;
  const bool global_damping = in.alpha_r != 0 || in.alpha_theta != 0;
  for (long k = lo; k < hi; ++k) {
    const long b = k - lo;
    const Vec3 v = Vec3(0.5 * (before.v[b] + p.v[k])), w = Vec3(0.5 * (before.w[b] + p.w[k]));
    // eq. P33-P34, P41: its contacts' forces as the force loop summed them for it, with its mean velocities.
    // A particle without contacts adds zeros, which change no bit of a FixedSum: skipped.
    const ParticleWork& pw = before.work[b];
    if (pw.damping.v != Vec3::Zero()) s.damping.add(pw.damping.v.dot(v) * dt);
    if (pw.tangential.v != Vec3::Zero() || pw.torque_per_radius.v != Vec3::Zero())
      s.tangential.add((pw.tangential.v.dot(v) + p.radius[k] * pw.torque_per_radius.v.dot(w)) * dt);
    if (in.rolling && pw.couple.v != Vec3::Zero()) s.rolling.add(pw.couple.v.dot(w) * dt);
    // eq. P40: the fluid's force as the force loop took it (x^n, v^{n-1/2}).
    if (in.fluid) s.fluid.add(in.fluid->force(p.radius[k], p.void_fraction[k], before.x[b], before.v[b], in.gravity).dot(v) * dt);
    const std::uint8_t fixed = in.any_fixed ? p.fixed[k] : 0;
    if (fixed == kPrescribed) {
      s.prescribed.add(-(in.force[k].v.dot(v) + in.torque[k].v.dot(w)) * dt);  // eq. P37
    } else if (!fixed && global_damping) {
      // eq. P35: the integrator's m (v+ - v-) = F Δt - α m v̄ Δt takes α m |v̄|² Δt.
      s.global.add((in.alpha_r * p.mass[k] * v.squaredNorm() + in.alpha_theta * p.inertia(k) * w.squaredNorm()) * dt);
    }
  }
}

}  // namespace dem
