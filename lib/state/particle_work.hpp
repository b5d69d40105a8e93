#pragma once
// The work of a step on the particles as the energy ledger sums it (StepWork; sim/energy_ledger.hpp,
// docs/physics.md eq. P33-P35, P37, P40-P41), and what it takes of the contacts' work on each
// particle: the force loop sums, per particle, its contacts' dashpot and tangential forces, n x f_t
// and rolling couples (ParticleWork), and once the particle has moved its work is those sums times
// its mean velocities (contact_work_terms). The motion takes it (integrate/motion.hpp MotionWork):
// it holds the velocities before and after the step at once.
#include <cstddef>
#include <vector>

#include "core/fixed_sum.hpp"
#include "state/load_sum.hpp"

namespace dem {

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

// Per particle, over its contacts as its net load sums them (+ where it is i, - where it is j;
// n x f_t + in both; a wall contact's after its pair contacts): Σ_k f_k · (v̄_i - v̄_j) = Σ_p F_p · v̄_p.
// A view of one array per sum, entry 0 a given particle's: the four-wide motion reads four
// particles' sums as it reads their loads (padded, aligned).
struct ParticleWork {
  LoadSum* damping = nullptr;            // Σ ± f_d n
  LoadSum* tangential = nullptr;         // Σ ± f_t
  LoadSum* torque_per_radius = nullptr;  // Σ n x f_t (times the radius: the contacts' torque)
  LoadSum* couple = nullptr;             // Σ ± M (rolling resistance); written only where the law has couples
  bool on() const { return damping != nullptr; }
  // The view whose entry 0 is this one's entry k (none where this is none).
  ParticleWork from(long k) const { return on() ? ParticleWork{damping + k, tangential + k, torque_per_radius + k, couple + k} : ParticleWork{}; }
};

// The arrays a ParticleWork views.
struct ParticleWorkArrays {
  std::vector<LoadSum> damping, tangential, torque_per_radius, couple;
  void resize(std::size_t n) { damping.resize(n), tangential.resize(n), torque_per_radius.resize(n), couple.resize(n); }
  ParticleWork view() { return {damping.data(), tangential.data(), torque_per_radius.data(), couple.data()}; }
};

// One particle's (or four particles', L = four lanes) contact work over the step [J] (eq. P33-P34,
// P41), from its sums' dot products with its mean velocities v̄ = (v^{n-1/2} + v^{n+1/2})/2 and w̄,
// each (x x' + y y') + z z': the dashpots' D · v̄ Δt, the tangential forces' (T · v̄ + a A · w̄) Δt,
// the couples' M · w̄ Δt. Written once over the lane type: the plain motion and the four-wide one
// give the same bits.
template <class L>
struct ContactWorkTerms {
  L damping, tangential, rolling;
};
template <class L>
[[gnu::always_inline]] inline ContactWorkTerms<L> contact_work_terms(const L& damping_v, const L& tangential_v, const L& torque_w,
                                                                      const L& couple_w, const L& radius, const L& dt) {
  return {damping_v * dt, (tangential_v + radius * torque_w) * dt, couple_w * dt};
}

}  // namespace dem
