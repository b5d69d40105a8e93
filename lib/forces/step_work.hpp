#pragma once
// The work of one step on the particles, for the energy ledger (sim/energy_ledger.hpp; docs/physics.md
// eq. P33-P35, P37, P40-P41), summed where its terms arise: each contact's law leaves its dashpot and
// tangential forces, the force loop sums them per particle (ParticleWork), and once a particle has
// moved its work is those times its mean velocity (add_particle_work). Within a step whose motion
// runs in the force loop, that is done block by block while the block is in cache; otherwise the
// ledger's pass does it after the motion, with the same function: the same bits either way.
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "contact/kinematics.hpp"
#include "core/fixed_sum.hpp"
#include "core/types.hpp"
#include "forces/fluid.hpp"
#include "state/load_sum.hpp"
#include "state/particles.hpp"

namespace dem {

// While the energy log is on: per particle, over its contacts as its net load sums them (+ where
// it is i, - where it is j; n x f_t + in both; a wall contact's after its pair contacts), their
// ContactWork, n x f_t and rolling couples, so that the ledger takes the contacts' work per
// particle: Σ_k f_k · (v̄_i - v̄_j) = Σ_p F_p · v̄_p.
struct ParticleWork {
  LoadSum damping;            // Σ ± f_d n
  LoadSum tangential;         // Σ ± f_t
  LoadSum torque_per_radius;  // Σ n x f_t (times the radius: the contacts' torque)
  LoadSum couple;             // Σ ± M (rolling resistance); written only where the law has couples
};

// What one step's forces did [J], each term exact (FixedSum): the same bits however the particles
// and contacts were split among threads.
struct StepWork {
  FixedSum damping;     // the normal dashpots', eq. P33
  FixedSum tangential;  // the tangential forces', eq. P34
  FixedSum rolling;     // the rolling couples', eq. P41
  FixedSum walls;       // put in by moving walls, eq. P37
  FixedSum prescribed;  // put in by what holds prescribed particles to their motion, eq. P37
  FixedSum fluid;       // the fluid's, eq. P40
  FixedSum global;      // taken by the global damping, eq. P35
  void add(const StepWork& o) {
    damping.add(o.damping), tangential.add(o.tangential), rolling.add(o.rolling), walls.add(o.walls);
    prescribed.add(o.prescribed), fluid.add(o.fluid), global.add(o.global);
  }
};

// What add_particle_work reads besides the particles (their state after the motion) and their
// BeforeMotion.
struct StepWorkInput {
  const LoadSum* force;   // the net loads the motion took (a prescribed particle's: what holds it)
  const LoadSum* torque;
  const FluidField* fluid;  // the stage's fluid, or null
  Vec3 gravity;
  double alpha_r, alpha_theta;  // the global damping (SimParams)
  double dt;
  bool rolling;    // some contact law has rolling couples
  bool any_fixed;  // Particles::fixed is to be read
};

// The state before the motion and the contacts' sums of particles [lo, hi), each array's first
// entry slot lo's: the ledger's arrays from lo on, or a block's own copies where nothing reads them
// after the step (the force loop's ThreadScratch: they stay in cache).
struct BeforeMotion {
  const Vec3* x;  // x^n (read only with a fluid: may be null without)
  const Vec3* v;  // v^{n-1/2}
  const Vec3* w;  // w^{n-1/2}
  const ParticleWork* work;
};

// Adds to `sums` the work on particles [lo, hi) of their contacts (ParticleWork), the fluid, what
// holds the prescribed ones and the global damping, each with the particle's mean velocities
// v̄ = (v^{n-1/2} + v^{n+1/2})/2, w̄ likewise (docs/physics.md eq. P33-P35, P37, P40-P41).
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
// at `v_wall`, spinning at `spin`): its forces join i's ParticleWork, to be taken with v̄_i, and
// what the wall's own motion makes of them goes to `terms`: f_d and f_t work on v̄_i - v_wall (eq.
// P33-P34), the wall puts in f · v_wall (eq. P37); a rolling couple M on i works on w̄_i - spin,
// the wall's drive puts in M · spin (eq. P41).
inline void add_wall_contact_work(const ContactWork& w, const ContactSum& s, const Vec3& couple, const Vec3& v_wall,
                                  const Vec3& spin, double dt, ParticleWork& pw, WallWorkTerms& terms) {
  pw.damping.v += w.damping;
  pw.tangential.v += w.tangential;
  pw.torque_per_radius.v += s.torque_per_radius;
  terms.damping.push_back(-w.damping.dot(v_wall) * dt);
  terms.tangential.push_back(-w.tangential.dot(v_wall) * dt);
  terms.walls.push_back(s.force.dot(v_wall) * dt);
  if (couple != Vec3::Zero()) {  // only a law with couples makes one: then pw.couple was summed
    pw.couple.v += couple;
    terms.walls.push_back(couple.dot(spin) * dt), terms.rolling.push_back(-couple.dot(spin) * dt);
  }
}

}  // namespace dem
