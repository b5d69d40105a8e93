#pragma once
// One step of motion (docs/physics.md eq. P3-P4; thesis eq. 2.38-2.47) once the force loop has summed each particle's net load
// (forces/force_loop.hpp ForceBlocks): its new velocities and position. Four particles at a time with
// AVX2 (simd/simd.hpp) where the processor has it, else one by one: per coordinate the same
// operations in the same order, so the same bits.
#include <cfloat>
#include <cmath>
#include <cstdint>

#include "core/types.hpp"
#include "state/load_sum.hpp"
#include "state/particle_work.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

// v^{n+1/2} = (a v^{n-1/2} + acc dt) b, a = 1 - alpha dt/2, b = 1/(1 + alpha dt/2), for the
// translation (ar, br) and the rotation (at, bt).
struct MotionConstants {
  double ar, br, at, bt, dt;
  PeriodicBox box;  // a particle that leaves the period comes back in at the other side
};

// The velocity or spin after the step (eq. P3-P4), written once for the plain step (S double,
// V Vec3) and the four-wide one (S and V four lanes, one coordinate of four particles):
// (a v + load dt_over_m) b, with dt / m for the translation and dt / I for the rotation.
template <class S, class V>
[[gnu::always_inline]] inline V next_velocity(const S& a, const V& v, const V& load, const S& dt_over_m, const S& b) {
  return (a * v + load * dt_over_m) * b;
}

// What the step reads and writes, as bare arrays (see CandidateArrays).
struct MotionArrays {
  Vec3* x;
  Vec3* v;
  Vec3* w;
  Vec3i* image;  // periods crossed
  const double* mass;
  const double* radius;
  const std::uint8_t* fixed;  // Particles::fixed; null where no particle is held or prescribed
  const LoadSum* force;       // the net loads of the force loop (ForceBlocks)
  const LoadSum* torque;
  // Where the state before the motion is kept (the energy ledger's x^n, v^{n-1/2}, w^{n-1/2}), or null.
  Vec3* before_x = nullptr;
  Vec3* before_v = nullptr;
  Vec3* before_w = nullptr;
};

// While the energy log is on: the particles' contact sums (state/particle_work.hpp), entry 0 the
// first moved particle's, whose work the motion takes as each particle moves, with its velocities
// before and after (contact_work_terms), adding it to `sums` (exactly: any order, the same bits).
struct MotionWork {
  ParticleWork contacts;
  bool couples;     // the contact law has rolling couples (else ParticleWork::couple is unread)
  StepWork* sums;   // its damping, tangential and rolling terms
};

// A step's motion as the force loop takes it, block by block once each block's loads are summed
// (forces/force_loop.hpp, ForceBlocks::motion).
struct MotionStep {
  MotionArrays arrays;
  MotionConstants constants;
};

// Particles [first, last): their state kept where asked (before_x...), then held ones stop,
// prescribed ones move at their own v and w, the others under their loads (all wrapped into the
// period).
// With `work`, their contacts' work (MotionWork).
// Returns the last particle whose new state is not finite (NaN or Inf in x, v or w makes a
// coordinate of x + v + w NaN or Inf; so does a sum beyond 1e308: a state as broken), or -1.
long move_particles(const MotionArrays& a, const MotionConstants& c, long first, long last, const MotionWork* work = nullptr);

}  // namespace dem
