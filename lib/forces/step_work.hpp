#pragma once
// The work of one step on the particles, for the energy ledger (sim/energy_ledger.hpp; docs/physics.md
// eq. P33-P35, P37, P40-P41), summed where its terms arise: each contact's law leaves its dashpot and
// tangential forces, the force loop sums them per particle (state/particle_work.hpp), and the
// motion takes their work as each particle moves (integrate/motion.hpp MotionWork). What else works
// on the particles (the fluid, what holds prescribed particles, the global damping) is taken once
// they have moved (add_particle_work): within a step whose motion runs in the force loop block by
// block while the block is in cache, otherwise by the ledger's pass after the motion, with the
// same function: the same bits either way.
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "contact/kinematics.hpp"
#include "core/types.hpp"
#include "forces/fluid.hpp"
#include "state/load_sum.hpp"
#include "state/particle_work.hpp"
#include "state/particles.hpp"

namespace dem {

// What add_particle_work reads besides the particles (their state after the motion) and their
// BeforeMotion.
struct StepWorkInput {
  const LoadSum* force;   // the net loads the motion took (a prescribed particle's: what holds it)
  const LoadSum* torque;
  const FluidField* fluid;  // the stage's fluid, or null
  Vec3 gravity;
  double alpha_r, alpha_theta;  // the global damping (SimParams)
  double dt;
  bool any_fixed;  // Particles::fixed is to be read
  bool global_damping() const { return alpha_r != 0 || alpha_theta != 0; }
  // Whether add_particle_work has a term to take (a fluid, prescribed particles or global damping).
  bool any() const { return fluid || any_fixed || global_damping(); }
};

// The state before the motion of particles [lo, hi), each array's first entry slot lo's: the
// ledger's arrays from lo on, or a block's own copies where nothing reads them after the step (the
// force loop's ThreadScratch: they stay in cache).
struct BeforeMotion {
  const Vec3* x;  // x^n (read only with a fluid: may be null without)
  const Vec3* v;  // v^{n-1/2}
  const Vec3* w;  // w^{n-1/2}
};

// Adds to `sums` the work on particles [lo, hi) of the fluid, what holds the prescribed ones and
// the global damping, each with the particle's mean velocities v̄ = (v^{n-1/2} + v^{n+1/2})/2, w̄
// likewise (docs/physics.md eq. P35, P37, P40); their contacts' is the motion's (MotionWork).
void add_particle_work(const Particles& p, const StepWorkInput& in, const BeforeMotion& before, long lo, long hi, StepWork& sums);

// The terms of the work of a block's wall contacts that their walls' motion makes (each an
// add_wall_contact_work's), added to the step's sums at once (add_to: one pass per term, not a
// FixedSum add per contact and term). A thread's own, kept with its memory between blocks.
struct WallWorkTerms {
  std::vector<double> damping, tangential, walls, rolling;
  // Adds them all to `sums`, and empties them.
  void add_to(StepWork& sums);
};

// A wall contact's part (what its law left: `w`, and its sum `s`, the force f on particle i and
// n x f_t; its rolling couple M, zero without one; the wall's material at the contact point moving
// at `v_wall`, spinning at `spin`): its forces join i's sums (entry e of `pw`), to be taken with v̄_i, and
// what the wall's own motion makes of them goes to `terms`: f_d and f_t work on v̄_i - v_wall (eq.
// P33-P34), the wall puts in f · v_wall (eq. P37); a rolling couple M on i works on w̄_i - spin,
// the wall's drive puts in M · spin (eq. P41).
inline void add_wall_contact_work(const ContactWork& w, const ContactSum& s, const Vec3& couple, const Vec3& v_wall,
                                  const Vec3& spin, double dt, const ParticleWork& pw, long e, WallWorkTerms& terms) {
  pw.damping[e].v += w.damping;
  pw.tangential[e].v += w.tangential;
  pw.torque_per_radius[e].v += s.torque_per_radius;
  terms.damping.push_back(-w.damping.dot(v_wall) * dt);
  terms.tangential.push_back(-w.tangential.dot(v_wall) * dt);
  terms.walls.push_back(s.force.dot(v_wall) * dt);
  if (couple != Vec3::Zero()) {  // only a law with couples makes one: then pw.couple was summed
    pw.couple[e].v += couple;
    terms.walls.push_back(couple.dot(spin) * dt), terms.rolling.push_back(-couple.dot(spin) * dt);
  }
}

}  // namespace dem
