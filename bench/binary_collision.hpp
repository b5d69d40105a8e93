#pragma once
// Binary collisions driven through the whole step (Simulation::advance: the force loop and the
// leapfrog), for the restitution tests (tests/test_restitution.cpp) and the table of
// bench/restitution_table.cpp: two spheres head-on (centre of mass at rest) or a sphere on a plane
// wall, no gravity, no friction, the first touch placed at a chosen fraction of a step.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/simulation.hpp"

namespace dem::collision {

// The linear spring and dashpot's closed forms (eq. 2.27-2.29 with m* and kn): the overlap
// u(t) = v/w_d exp(-gamma w t) sin(w_d t), w = sqrt(kn/m*), w_d = w sqrt(1 - gamma^2), so the
// contact lasts t_c = pi/w_d, the rebound speed is eta v, and the peak overlap, where u' = 0 at
// w_d t* = atan2(sqrt(1 - gamma^2), gamma), is v/w exp(-gamma w t*).
struct Closed {
  double duration, peak_overlap, restitution;
};
inline Closed linear_closed_form(double kn, double m_eff, double eta, double v) {
  const double gamma = damping_ratio(eta), w = std::sqrt(kn / m_eff), s = std::sqrt(1 - gamma * gamma);
  const double w_d = w * s;
  return {std::numbers::pi / w_d, v / w * std::exp(-gamma * w * std::atan2(s, gamma) / w_d), eta};
}

struct Result {
  double restitution = 0, duration = 0, peak_overlap = 0;
  EnergyLedger ledger;  // at the release, where Shot::ledger
};

constexpr double kA = 1e-3, kB = 1.5e-3, kDensityA = 2500, kDensityB = 7800;

struct Shot {
  NormalLaw law = NormalLaw::Cundall;
  bool wall = false;          // a sphere on a plane wall, else two spheres (radii a, b)
  double eta = 0.5;           // restitution asked
  double steps = 50;          // steps per contact: dt = t_ref / steps
  double t_ref = 0;           // the contact time the step is measured against [s]
  double phase = 0;           // where within a step the first touch falls, [0, 1)
  double v = 0.5;             // approach speed [m/s]
  double kn = 1e5;            // cundall [N/m]
  double young = 1e7, poisson = 0.25;  // hertz, sphere a (and b unless set below)
  double young_b = 0, poisson_b = 0;   // hertz, sphere b and the wall; 0: as sphere a
  bool ledger = false;        // keep the energy ledger (sim/energy_ledger.hpp)
  bool explicit_dashpot = false;  // docs/contact-laws.md eq. D7 in place of D1-D6
  double radius_b = kB, density_b = kDensityB;  // sphere b
};

inline double mass(double r, double density) { return density * 4.0 / 3.0 * std::numbers::pi * r * r * r; }
inline double effective_mass(bool wall) {
  const double ma = mass(kA, kDensityA), mb = mass(kB, kDensityB);
  return wall ? ma : ma * mb / (ma + mb);
}

inline Material material(const Shot& s, bool b) {
  Material m;
  m.name = b ? "b" : "a";
  m.law = s.law;
  m.density = b ? s.density_b : kDensityA;
  m.kn = s.kn;
  m.kt = s.kn;
  m.young_modulus = b && s.young_b > 0 ? s.young_b : s.young;
  m.poisson_ratio = b && s.poisson_b > 0 ? s.poisson_b : s.poisson;
  m.friction_angle = 0;
  m.restitution = s.eta;
  m.restitution_t = 1;
  m.explicit_dashpot = s.explicit_dashpot;
  return m;
}

// One collision; restitution = separation speed after / approach speed before.
inline Result collide(const Shot& s) {
  Simulation sim;
  sim.materials = MaterialTable({material(s, false), material(s, true)}, {});
  sim.params.gravity = Vec3::Zero();
  sim.dt = s.t_ref / s.steps;
  sim.ledger.on = s.ledger;
  const double v = s.v;
  const double gap = (3 + s.phase) * v * sim.dt;  // the first touch at this fraction of the fourth step
  const double rb = s.radius_b;
  const double ma = mass(kA, kDensityA), mb = mass(rb, s.density_b);
  if (s.wall) {
    sim.walls.push_back(Wall{"floor", 1, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
    sim.particles.add(0, Vec3(0, 0, kA + gap), kA, kDensityA, 0);
    sim.particles.v[0] = Vec3(0, 0, -v);
  } else {
    sim.particles.add(0, Vec3(0, 0, kA + rb + gap), kA, kDensityA, 0);
    sim.particles.add(1, Vec3(0, 0, 0), rb, s.density_b, 1);
    sim.particles.v[0] = Vec3(0, 0, -v * mb / (ma + mb));  // centre of mass at rest
    sim.particles.v[1] = Vec3(0, 0, v * ma / (ma + mb));
  }
  const auto overlap = [&] {
    return s.wall ? kA - sim.particles.x[0].z() : kA + rb - (sim.particles.x[0] - sim.particles.x[1]).norm();
  };
  const auto approach = [&] { return s.wall ? -sim.particles.v[0].z() : sim.particles.v[1].z() - sim.particles.v[0].z(); };
  Result r;
  double before = overlap(), t_in = -1;
  for (int n = 0; n < 40 * s.steps + 10; ++n) {
    sim.advance();
    const double now = overlap();
    r.peak_overlap = std::max(r.peak_overlap, now);
    // Touch and release: the zero crossings of the overlap, which moves linearly within a step.
    if (before <= 0 && now > 0) t_in = sim.time - sim.dt * now / (now - before);
    if (before > 0 && now <= 0) {
      r.duration = sim.time - sim.dt * now / (now - before) - t_in;
      break;
    }
    before = now;
  }
  r.restitution = -approach() / v;
  r.ledger = sim.ledger;
  return r;
}

}  // namespace dem::collision
