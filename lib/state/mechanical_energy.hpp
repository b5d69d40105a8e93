#pragma once
// The particles' kinetic (translational + rotational) and gravitational potential energy -Σ m g·x
// (x unwrapped across periodic boundaries: flowing down a periodic chute releases energy), summed
// over runs of storage slots: the energy check's sum (sim/energy_audit.hpp), taken by the force
// loop run by run before each run of particles moves, or by a pass of its own.
#include <vector>

#include "core/types.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

struct MechanicalEnergy {
  double kinetic = 0;     // translational + rotational
  double rotational = 0;  // the rotational part of `kinetic`
  double potential = 0;
  double total() const { return kinetic + potential; }
};

// Kinetic energy of particle k, translational + rotational ½ I ω² (the second part in `rotational`).
inline double kinetic_energy_of(const Particles& p, std::size_t k, double& rotational) {
  rotational = 0.5 * p.inertia(k) * p.w[k].squaredNorm();
  return 0.5 * p.mass[k] * p.v[k].squaredNorm() + rotational;
}

// Particle k's energy added to e.
inline void add_energy_of(const Particles& p, const Vec3& gravity, const PeriodicBox& box, std::size_t k, MechanicalEnergy& e) {
  double rotational;
  e.kinetic += kinetic_energy_of(p, k, rotational);
  e.rotational += rotational;
  e.potential -= p.mass[k] * gravity.dot(box.unwrapped(p.x[k], p.image[k]));
}

// The energy of slots [lo, hi), added in slot order from zero.
inline MechanicalEnergy energy_of_slots(const Particles& p, const Vec3& gravity, const PeriodicBox& box, long lo, long hi) {
  MechanicalEnergy e;
  for (long k = lo; k < hi; ++k) add_energy_of(p, gravity, box, static_cast<std::size_t>(k), e);
  return e;
}

// The runs' sums added in their order from zero: with runs of fixed slots, the same bits for any
// thread count, whoever summed each run.
inline MechanicalEnergy sum_in_order(const std::vector<MechanicalEnergy>& runs) {
  MechanicalEnergy e;
  for (const MechanicalEnergy& s : runs) e.kinetic += s.kinetic, e.rotational += s.rotational, e.potential += s.potential;
  return e;
}

}  // namespace dem
