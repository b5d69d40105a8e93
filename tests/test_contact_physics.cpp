// Verification of the `cundall` contact law and the integrator against closed-form answers:
// a linear spring-dashpot collision has restitution eta (Tsuji's damping, eq. 2.27-2.29) and lasts
// the damped half-period pi / omega_d, omega_d = omega_0 sqrt(1 - gamma^2), omega_0 = sqrt(k / m*).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/simulation.hpp"

namespace dem {
namespace {

Material glass(double eta) {
  Material m;
  m.name = "glass";
  m.density = 2500;
  m.kn = 1e4;
  m.kt = 1e4;
  m.friction_angle = 0;
  m.restitution = eta;
  m.restitution_t = eta;
  return m;
}

struct Impact {
  double restitution;
  double duration;
};

// Two equal spheres approaching head-on at +-v0 (or one sphere onto a wall); no gravity.
Impact collide(double eta, bool against_wall) {
  Simulation sim;
  sim.materials = MaterialTable({glass(eta)}, {});
  sim.params.gravity = Vec3::Zero();
  const double a = 0.001, v0 = 0.1;
  sim.particles.add(0, Vec3(0, 0, 0.0012), a, 2500, 0);
  if (against_wall) {
    sim.walls.push_back(Wall{"floor", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
    sim.particles.v[0] = Vec3(0, 0, -v0);
  } else {
    sim.particles.add(1, Vec3(0, 0, -0.0012), a, 2500, 0);
    sim.particles.v[0] = Vec3(0, 0, -v0);
    sim.particles.v[1] = Vec3(0, 0, v0);
  }
  // FRAC 0.01: about 300 steps per contact, so the O(dt) error of the half-step damping velocity
  // stays far below the 1 % tolerance.
  sim.dt = 0.01 * sim.critical_time_step();
  int contact_steps = 0;
  bool touched = false;
  for (int s = 0; s < 200000; ++s) {
    sim.advance();
    const bool in_contact = sim.pair_contacts.size() + sim.wall_contacts.size() > 0;
    contact_steps += in_contact;
    touched = touched || in_contact;
    if (touched && !in_contact) break;
  }
  const double v_after = against_wall ? sim.particles.v[0].z() : sim.particles.v[0].z() - sim.particles.v[1].z();
  const double v_before = against_wall ? -v0 : -2 * v0;
  return {-v_after / v_before, contact_steps * sim.dt};
}

double damped_half_period(double eta, double m_eff, double k) {
  const double l = std::log(eta);
  const double gamma = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  return std::numbers::pi / (std::sqrt(k / m_eff) * std::sqrt(1 - gamma * gamma));
}

class NormalImpact : public ::testing::TestWithParam<double> {};

TEST_P(NormalImpact, SphereSphereRestitutionAndDuration) {
  const double eta = GetParam();
  const Impact r = collide(eta, false);
  const double m = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-9;
  EXPECT_NEAR(r.restitution, eta, 0.01 * eta) << "restitution within 1 % of eta";
  EXPECT_NEAR(r.duration, damped_half_period(eta, m / 2, 1e4), 0.02 * r.duration) << "duration within 2 % of pi/omega_d";
}

TEST_P(NormalImpact, SphereWallRestitutionAndDuration) {
  const double eta = GetParam();
  const Impact r = collide(eta, true);
  const double m = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-9;
  EXPECT_NEAR(r.restitution, eta, 0.01 * eta);
  EXPECT_NEAR(r.duration, damped_half_period(eta, m, 1e4), 0.02 * r.duration);
}

INSTANTIATE_TEST_SUITE_P(Restitution, NormalImpact, ::testing::Values(0.3, 0.5, 0.9, 1.0));

// Free fall under gravity: the central-difference scheme is exact for constant acceleration, so
// position and velocity after n steps match the closed form to round-off (1e-12 relative: n = 1000
// additions of g dt accumulate a few ulps).
TEST(Integrator, FreeFallMatchesConstantAcceleration) {
  Simulation sim;
  sim.materials = MaterialTable({glass(0.5)}, {});
  sim.particles.add(0, Vec3::Zero(), 0.001, 2500, 0);
  sim.dt = 1e-4;
  const int n = 1000;
  for (int s = 0; s < n; ++s) sim.advance();
  // v_{1/2} = g dt, x_n = sum_{k=1..n} g k dt^2 = g dt^2 n (n + 1) / 2.
  const double expected = -9.81 * sim.dt * sim.dt * n * (n + 1) / 2.0;
  EXPECT_NEAR(sim.particles.x[0].z(), expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(sim.particles.v[0].z(), -9.81 * sim.dt * n, 1e-12 * 9.81 * sim.dt * n);
}

// Global damping (eq. 2.36-2.38): a free particle's velocity decays by (1 - a dt/2)/(1 + a dt/2) per step.
TEST(Integrator, GlobalDampingFactor) {
  Simulation sim;
  sim.materials = MaterialTable({glass(0.5)}, {});
  sim.params.gravity = Vec3::Zero();
  sim.params.alpha_r = 50;
  sim.particles.add(0, Vec3::Zero(), 0.001, 2500, 0);
  sim.particles.v[0] = Vec3(1, 0, 0);
  sim.dt = 1e-4;
  for (int s = 0; s < 100; ++s) sim.advance();
  const double f = (1 - 50 * 1e-4 / 2) / (1 + 50 * 1e-4 / 2);
  EXPECT_NEAR(sim.particles.v[0].x(), std::pow(f, 100), 1e-12);
}

// Coulomb sliding: a sphere launched along a frictional floor without spin slides, then rolls at
// 5/7 of its initial speed (angular momentum about the contact point is conserved).
TEST(Friction, SlidingSphereEndsRollingAtFiveSevenths) {
  Simulation sim;
  Material m = glass(0.5);
  m.friction_angle = std::atan(0.3) * 180 / std::numbers::pi;
  m.kn = m.kt = 1e5;
  sim.materials = MaterialTable({m}, {});
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
  const double a = 0.001;
  const double m_p = 2500 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  // Start at the static overlap m g / k so the normal force is steady.
  sim.particles.add(0, Vec3(0, 0, a - m_p * 9.81 / 1e5), a, 2500, 0);
  sim.particles.v[0] = Vec3(0.05, 0, 0);
  sim.dt = 0.02 * sim.critical_time_step();
  const double t_end = 2 * 0.05 / (0.3 * 9.81);  // sliding lasts 2 v0 / (7 mu g); run longer
  while (sim.time < t_end) sim.advance();
  EXPECT_NEAR(sim.particles.v[0].x(), 5.0 / 7.0 * 0.05, 0.01 * 0.05) << "final speed 5/7 v0 within 1 % of v0";
  EXPECT_NEAR(sim.particles.w[0].y() * a, sim.particles.v[0].x(), 0.01 * 0.05) << "rolling without slip: w a = v";
}

}  // namespace
}  // namespace dem
