// Periodic boundaries and particles fixed in place, against closed-form answers: a head-on collision
// across a periodic boundary has the restitution eta of the material (Tsuji's damping, eq.
// 2.27-2.29) and conserves momentum, as the same collision inside the period; a sphere bouncing on a
// fixed sphere rebounds with -eta v (the fixed one is infinitely heavy, as LAMMPS's fix freeze); and a
// periodic chute (gravity along a periodic axis) does not trip the energy check, whose potential
// energy counts the periods each particle has crossed.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

Material bead(double eta) {
  Material m;
  m.name = "bead";
  m.kn = m.kt = 1e4;
  m.friction_angle = 0;
  m.restitution = m.restitution_t = eta;
  return m;
}

PeriodicBox periodic_x(double length) {
  PeriodicBox box;
  box.axis = {true, false, false};
  box.hi = Vec3(length, 0, 0);
  return box;
}

// Runs one binary collision to its end at FRAC = 0.001 (as tests/test_contact_physics.cpp: eta to
// 1 %). Returns whether the spheres touched.
bool collide(Simulation& sim) {
  sim.dt = 0.001 * sim.critical_time_step();
  bool touched = false;
  for (int s = 0; s < 200000; ++s) {
    sim.advance();
    const bool in_contact = sim.pair_contacts().size() > 0;
    touched = touched || in_contact;
    if (touched && !in_contact) break;
  }
  return touched;
}

// Two equal spheres approaching head-on along x at +-v0, their midpoint at x = centre; runs until
// they part. Returns the velocities after.
std::pair<Vec3, Vec3> collide_along_x(double centre, double eta) {
  Simulation sim;
  sim.materials = MaterialTable({bead(eta)}, {});
  sim.params.gravity = Vec3::Zero();
  const double a = 0.001, v0 = 0.1, L = 0.01;
  sim.particles.add(0, Vec3(centre - 1.2 * a, 0, 0), a, 2500, 0);
  sim.particles.add(1, Vec3(centre + 1.2 * a, 0, 0), a, 2500, 0);
  sim.particles.v[0] = Vec3(v0, 0, 0);
  sim.particles.v[1] = Vec3(-v0, 0, 0);
  sim.set_periodic(periodic_x(L));
  EXPECT_TRUE(collide(sim));
  return {sim.particles.v[0], sim.particles.v[1]};
}

TEST(Periodic, CollisionAcrossTheBoundaryAsInside) {
  const double eta = 0.5, v0 = 0.1;
  const auto [inside0, inside1] = collide_along_x(0.005, eta);  // the middle of the period
  const auto [across0, across1] = collide_along_x(0.0, eta);    // straddling x = 0 = L
  // Restitution within 1 % of eta (the half-step dashpot's error at this step, test_contact_physics).
  EXPECT_NEAR((across1.x() - across0.x()) / (2 * v0), eta, 0.01 * eta);
  // Momentum: equal masses, so the velocities sum to zero (to round-off of the forces).
  EXPECT_NEAR(across0.x() + across1.x(), 0.0, 1e-12 * v0);
  // The same collision: only the positions' rounding differs.
  EXPECT_NEAR(across0.x(), inside0.x(), 1e-9 * v0);
  EXPECT_NEAR(across1.x(), inside1.x(), 1e-9 * v0);
}

TEST(Fixed, BounceOnAHeldSphereHasRestitutionEta) {
  for (double eta : {0.3, 0.8}) {
    Simulation sim;
    sim.materials = MaterialTable({bead(eta)}, {});
    sim.params.gravity = Vec3::Zero();
    const double a = 0.001, v0 = 0.1;
    sim.particles.add(0, Vec3(0, 0, 0), a, 2500, 0);
    sim.particles.fixed[0] = 1;
    sim.particles.add(1, Vec3(0, 0, 2.2 * a), a, 2500, 0);
    sim.particles.v[1] = Vec3(0, 0, -v0);
    ASSERT_TRUE(collide(sim));
    // m* = m of the moving sphere (the fixed one is infinitely heavy): it rebounds at eta v0,
    // within 1 % as against a wall (tests/test_contact_physics.cpp).
    EXPECT_NEAR(sim.particles.v[1].z(), eta * v0, 0.01 * eta * v0) << "eta " << eta;
    EXPECT_EQ(sim.particles.x[0], Vec3::Zero()) << "a fixed particle never moves";
    EXPECT_EQ(sim.particles.v[0], Vec3::Zero());
    EXPECT_EQ(sim.particles.w[0], Vec3::Zero());
  }
}

// A periodic chute: a base of held spheres on a square lattice, 200 free spheres above, gravity
// tilted 40 degrees along x (steeper than LAMMPS's chute benchmark, so that it flows at once). The free ones flow down the slope and
// cross the period many times; their unwrapped potential energy falls without jumps, and the energy
// check (max_energy_gain 0.5) stays quiet. Counting wrapped positions instead would add m g_x L at
// every crossing (checked by breaking the unwrapping on purpose: the check fires).
TEST(Periodic, ChuteFlowKeepsTheEnergyBalance) {
  Simulation sim;
  Material m = bead(0.5);
  m.friction_angle = 26;
  sim.materials = MaterialTable({m}, {});
  const double d = 0.002, L = 10 * d, g = 9.81, angle = 40 * M_PI / 180;
  sim.params.gravity = Vec3(g * std::sin(angle), 0, -g * std::cos(angle));
  Index id = 0;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      sim.particles.add(id, Vec3((i + 0.5) * d, (j + 0.5) * d, 0.5 * d), 0.5 * d, 2500, 0);
      sim.particles.fixed[id++] = 1;
    }
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) sim.particles.add(id++, Vec3((i + 0.5) * d, (j + 0.5) * d, (1.5 + 1.05 * k) * d), 0.5 * d, 2500, 0);
  PeriodicBox box;
  box.axis = {true, true, false};
  box.hi = Vec3(L, L, 0);
  sim.set_periodic(box);
  sim.dt = 0.05 * sim.critical_time_step();
  long crossings = 0;
  for (int s = 0; s < 50000; ++s) {
    const std::vector<Vec3i> before = sim.particles.image;
    ASSERT_NO_THROW(sim.advance()) << "step " << s;
    for (std::size_t k = 0; k < before.size(); ++k) crossings += sim.particles.image[k] != before[k];
  }
  EXPECT_GT(crossings, 50) << "the free spheres must cross the period";
  const EnergyBalance& b = sim.energy_balance();
  EXPECT_LT(b.now.potential, b.start.potential) << "unwrapped, the potential energy falls as the spheres flow down";
  EXPECT_LT(b.excess(), 0.0) << "no energy is created";
  for (std::size_t k = 0; k < 100; ++k) EXPECT_EQ(sim.particles.v[k], Vec3::Zero());
}

}  // namespace
}  // namespace dem
