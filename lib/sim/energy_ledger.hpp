#pragma once
// The energy balance of a run (docs/physics.md eq. P29-P45), kept only when asked (run-stage's
// energy log): each step it adds what the step dissipated, released and put in, and, at the steps
// whose figures are read (measure_now), measures what the particles and contacts hold. The work
// is taken where it arises (forces/step_work.hpp): each contact's law leaves its dashpot and
// tangential forces, the force loop sums them per particle and the motion takes their work as it
// moves each particle (integrate/motion.hpp MotionWork). The pass after the motion
// (account_energy) takes what is held, the energy of bonds that broke, and the particles' other
// work (a fluid, prescribed particles, global damping) on a step whose motion ran apart. A run
// that does not ask pays one test per step and one per group of contacts of the force loop.
//
// The scheme follows the integrator (leapfrog): the force at step n acts on the velocity between
// the half steps n-1/2 and n+1/2, so the kinetic energy changes by exactly F · (v^{n-1/2} +
// v^{n+1/2})/2 Δt. Every work is therefore taken with the mean of the two half-step velocities,
// the kinetic energy at the half step n+1/2, the potential energy at the mean of x^n and x^{n+1},
// and each contact's elastic energy at the half step too (eq. P31): the balance is then exact but
// for the elastic energy of non-linear laws and the breaking of bonds, both O(Δt²).
//
// Every sum is exact in fixed point (FixedSum), so the figures have the same bits whatever the
// storage order of particles and contacts and the thread count.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/fixed_sum.hpp"

namespace dem {

// What the ledger has accumulated since its reference (the end of the first step it saw) [J].
struct EnergyTotals {
  double damping_normal = 0;    // the normal dashpot's work, eq. P33
  double tangential_work = 0;   // work of the tangential forces on the particles, eq. P34
  double global_damping = 0;    // eq. P35
  double released = 0;          // elastic energy of bonds when they broke, eq. P36
  double work_walls = 0;        // by moving walls, eq. P37
  double work_prescribed = 0;   // by what holds the prescribed particles to their motion, eq. P37
  double work_abs = 0;          // Σ |each step's input| (the scale, eq. P39)
  double work_fluid = 0;        // by the fluid's drag, pressure gradient and buoyancy, eq. P40
  double rolling_work = 0;      // of the rolling couples on the particles, eq. P41
  double fibres_released = 0;   // elastic energy of fibre segments when they broke, eq. P44
  double inserted = 0;          // kinetic + potential energy of particles inserted, eq. P45
};

// What the particles and contacts hold at the half step just reached [J].
struct EnergyState {
  double kinetic_translation = 0, kinetic_rotation = 0;
  double potential = 0;           // gravity, at the mean of x^n and x^{n+1} (unwrapped)
  double elastic_normal = 0;      // eq. P31, bonds included
  double elastic_tangential = 0;  // the tangential springs, ½ |f_s|² / k_t
  double elastic_rolling = 0;     // the rolling springs (epsd2), ½ |M|² / k_r, eq. P42
  double elastic_fibres = 0;      // the fibres' intact segments, eq. P43
  double total() const {
    return kinetic_translation + kinetic_rotation + potential + elastic_normal + elastic_tangential + elastic_rolling + elastic_fibres;
  }
};

struct EnergyLedger {
  bool on = false;         // accumulate (Simulation::advance)
  // Whether the next step measures what is held (`now`): the work is added every step, but the
  // state is needed only where a figure is read (the energy log's rows), and measuring it is most
  // of the pass. The first step accounted always measures (the reference).
  bool measure_now = true;
  bool have_reference = false;
  // Whether the next step accounted measures what is held: where asked, and at the reference.
  bool measures() const { return measure_now || !have_reference; }
  EnergyState reference;   // at the end of the first step accounted
  EnergyTotals totals;
  EnergyState now;         // at the last step that measured it

  // Friction and the tangential dashpot together, eq. P34: what the tangential forces took from the
  // particles less what the springs now hold more than at the reference.
  double friction() const { return -totals.tangential_work - (now.elastic_tangential - reference.elastic_tangential); }
  // Rolling resistance, eq. P42: what the couples took from the particles less what the rolling
  // springs now hold more than at the reference.
  double rolling() const { return -totals.rolling_work - (now.elastic_rolling - reference.elastic_rolling); }
  double dissipated() const { return totals.damping_normal + friction() + totals.global_damping + rolling(); }
  double released() const { return totals.released + totals.fibres_released; }
  // Work from outside and energy brought in by inserted particles (eq. P37, P40, P45).
  double input() const { return totals.work_walls + totals.work_prescribed + totals.work_fluid + totals.inserted; }
  // eq. P38: held + dissipated + released - input - held at the reference (0 in a closed balance).
  double error() const { return now.total() + dissipated() + released() - input() - reference.total(); }
  // eq. P39: the energy at the reference that can move (kinetic and elastic), plus the input and the
  // change in potential energy since.
  double scale() const;

  // The checkpoint's form (/run/energy): every double above, in a fixed order; from_values throws
  // std::invalid_argument on a wrong count (kValues).
  static constexpr std::size_t kValues = 26;
  std::vector<double> values() const;
  void from_values(const std::vector<double>& v);
};

}  // namespace dem
