// Love-Weber stress (SPEC §11, lib/post/stress.hpp) on hand-built configurations whose answers
// are worked out by hand: sigma_ab = (1/V) sum_c f_a b_b, tension positive (docs/post.md).
// Tolerances are round-off (1e-12 relative) unless said otherwise: every answer is a few exact
// products and sums of the same numbers.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "post/contact_forces.hpp"
#include "post/stress.hpp"
#include "sim/simulation.hpp"

#include "post_lattice.hpp"

namespace dem {
namespace {

constexpr double kTol = 1e-12;

Material spring_only(double kn) {
  Material m;
  m.name = "m";
  m.kn = m.kt = kn;
  m.friction_angle = 30;
  m.restitution = m.restitution_t = 1.0;  // no dashpot: the force is k_n u alone
  return m;
}

// Two spheres pressed together along x by a known force F (on i, pointing away from j):
// sigma_xx = -F l / V (l the branch length) over a box of volume V holding both, all other
// components zero; per particle the arm is the distance from the centre to the middle of the
// overlap, (a_i - a_j + l)/2 for i, so sigma_i,xx = -F (a_i - a_j + l) / (2 V_i).
TEST(LoveWeber, TwoSpheresPressedAlongX) {
  const double ai = 1e-3, aj = 1.5e-3, l = 2.4e-3, F = 0.7;
  Particles p;
  p.add(0, Vec3(0.01, 0.02, 0.03), ai, 2500, 0);
  p.add(1, Vec3(0.01 + l, 0.02, 0.03), aj, 2500, 0);
  ContactForceSet c;
  c.pair_i = {0};
  c.pair_j = {1};
  c.pair_force = {Vec3(-F, 0, 0)};
  c.pair_normal = {Vec3::UnitX()};
  c.pair_bonded = {0};
  const ParticleStress s = particle_stress(p, c);
  const std::vector<Mat3> sig = particle_stress_tensors(p, s);
  const double Vi = 4.0 / 3.0 * std::numbers::pi * ai * ai * ai, Vj = 4.0 / 3.0 * std::numbers::pi * aj * aj * aj;
  EXPECT_NEAR(sig[0](0, 0), -F * (ai - aj + l) / 2 / Vi, kTol * F * l / Vi);
  EXPECT_NEAR(sig[1](0, 0), -F * (aj - ai + l) / 2 / Vj, kTol * F * l / Vj);
  EXPECT_EQ(s.contacts[0], 1);
  EXPECT_EQ(s.contacts[1], 1);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (a + b > 0) EXPECT_EQ(sig[0](a, b), 0.0) << a << b;

  const Box box{Vec3(0, 0, 0), Vec3(0.02, 0.04, 0.05)};
  const BoxAverage avg = box_average(p, s, box);
  EXPECT_EQ(avg.count, 2u);
  EXPECT_NEAR(avg.contact(0, 0), -F * l / box.volume(), kTol * F * l / box.volume());
  EXPECT_NEAR(pressure_of(avg.contact), F * l / box.volume() / 3, kTol * F * l / box.volume()) << "compression: positive pressure";
}

// The same through the simulation: the force comes from the contact law (k_n u, no damping) at
// the state as it stands, recomputed as post-macro does for a checkpoint.
TEST(LoveWeber, ForceFromTheStateAsACheckpointHoldsIt) {
  const double a = 1e-3, kn = 2e4, l = 1.99e-3;
  Simulation sim;
  sim.materials = MaterialTable({spring_only(kn)}, {});
  sim.params.gravity = Vec3::Zero();
  sim.particles.add(0, Vec3(0, 0, 0), a, 2500, 0);
  sim.particles.add(1, Vec3(0, 0, l), a, 2500, 0);  // along z this time
  sim.dt = 1e-7;
  const ContactForceSet c = contact_forces_at_state(sim);
  ASSERT_EQ(c.pairs(), 1u);
  EXPECT_EQ(sim.particles.x[1], Vec3(0, 0, l)) << "the state is not advanced";
  const double F = kn * (2 * a - l);
  EXPECT_NEAR(c.pair_force[0][2], -F, 1e-12 * F);
  const Box box{Vec3(-a, -a, -a), Vec3(a, a, l + a)};
  const BoxAverage avg = box_average(sim.particles, particle_stress(sim.particles, c), box);
  EXPECT_NEAR(avg.contact(2, 2), -F * l / box.volume(), 1e-12 * F * l / box.volume());
  EXPECT_NEAR(avg.contact(0, 0), 0.0, 1e-20);
}

// The forces of a state as post-macro recomputes them, on samples on both sides of the size above
// which a step sorts the storage (SimParams::sort_min_particles) and at a step where it sorts (a
// multiple of sort_every): every record names the particles the force acts between. Answer by
// hand: spheres at rest with no spring history carry k_n u along the branch, u from their
// positions (round-off tolerance, 1e-12 of the force). Spheres on a jittered cubic lattice whose
// spacing is below the diameter (about six contacts each), stored in a shuffled order so that a
// sort moves every one; 22^3 = 10,648 lies above the threshold of 10^4, 21^3 = 9,261 below.
// (A step that sorts the copy it computes on put the forces on the wrong particles: a settled
// 12,000-sphere sample gave twice the pressure.)
TEST(LoveWeber, ForcesOfTheStateNameTheirParticlesWhereAStepWouldSort) {
  for (const int n : {21, 22}) {
    const double a = 1e-3, s = 1.98e-3, kn = 2e4;
    Simulation sim;
    sim.materials = MaterialTable({spring_only(kn)}, {});
    sim.params.gravity = Vec3::Zero();
    sim.params.sort_every = 1000;
    sim.params.sort_min_particles = 10000;
    sim.dt = 1e-7;
    sim.step = 3000;
    std::vector<int> place(n * n * n);
    for (int k = 0; k < n * n * n; ++k) place[k] = k;
    std::mt19937 rng(7);
    std::shuffle(place.begin(), place.end(), rng);
    std::uniform_real_distribution<double> jitter(-0.004 * a, 0.004 * a);
    for (int q : place) {
      const Vec3 lattice(q % n, (q / n) % n, q / (n * n));
      sim.particles.add(q, lattice * s + Vec3(jitter(rng), jitter(rng), jitter(rng)), a, 2500, 0);
    }
    const std::vector<Vec3> x = sim.particles.x;
    const ContactForceSet c = contact_forces_at_state(sim);
    EXPECT_EQ(sim.particles.x, x) << "the state is not advanced";
    // Lattice neighbours overlap (|d| <= s + 0.014 a < 2a), others do not (|d| >= 1.41 s - 0.014 a).
    const long neighbours = 3L * n * n * (n - 1);
    ASSERT_EQ(static_cast<long>(c.pairs()), neighbours) << n;
    long wrong = 0;
    for (std::size_t k = 0; k < c.pairs(); ++k) {
      const int i = c.pair_i[k], j = c.pair_j[k];
      const Vec3 d = x[j] - x[i];
      const double u = 2 * a - d.norm();
      const Vec3 want = -kn * u * d.normalized();
      if (!(u > 0) || (c.pair_force[k] - want).norm() > 1e-12 * kn * u) ++wrong;
    }
    EXPECT_EQ(wrong, 0) << n << "^3 spheres: records whose force is not that of their two particles";
  }
}

// A sphere of radius a resting on a wall z = 0 with its centre at height a - u: the wall pushes
// with k_n u at the contact point (x, y, 0), so sigma_zz = -k_n u (a - u) / V_p.
TEST(LoveWeber, WallContactActsAtThePointOnTheWall) {
  const double a = 1e-3, kn = 3e4, u = 2e-6;
  Simulation sim;
  sim.materials = MaterialTable({spring_only(kn)}, {});
  sim.params.gravity = Vec3::Zero();
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
  sim.particles.add(0, Vec3(0.1, 0.2, a - u), a, 2500, 0);
  sim.dt = 1e-7;
  const ContactForceSet c = contact_forces_at_state(sim);
  ASSERT_EQ(c.walls(), 1u);
  EXPECT_EQ(c.wall_point[0], Vec3(0.1, 0.2, 0));
  const std::vector<Mat3> sig = particle_stress_tensors(sim.particles, particle_stress(sim.particles, c));
  const double V = 4.0 / 3.0 * std::numbers::pi * a * a * a, want = -kn * u * (a - u) / V;
  EXPECT_NEAR(sig[0](2, 2), want, 1e-9 * std::abs(want));  // the force k_n u carries the round-off of u = a - (a - u)
  EXPECT_NEAR(sig[0](0, 0), 0.0, 1e-20);
}

// A simple cubic lattice (spacing s) with the same force on every contact: x-contacts carry
// (-Fx, tau, 0) on their lower-x particle, y-contacts (0, -Fy, 0), z-contacts (0, 0, -Fz). Over a
// box of whole lattice cells around interior particles the stress is force per cell face:
// sigma_xx = -Fx/s^2, sigma_yy = -Fy/s^2, sigma_zz = -Fz/s^2, and sigma_yx = tau/s^2 (force index
// first: y-force carried across x-faces), sigma_xy = 0.
TEST(LoveWeber, CubicLatticeEqualsForcePerArea) {
  const int n = 6;
  const double s = 2e-3, a = 1e-3, Fx = 0.5, Fy = 0.3, Fz = 0.9, tau = 0.05;
  const test::LoadedLattice lattice = test::loaded_lattice(n, s, a, Fx, Fy, Fz, tau);
  const Particles& p = lattice.p;
  const ContactForceSet& c = lattice.c;
  const ParticleStress ps = particle_stress(p, c);
  // Particles 1..4 along each axis, each with its whole cell: [0.5 s, 4.5 s]^3.
  const Box box{Vec3::Constant(0.5 * s), Vec3::Constant(4.5 * s)};
  const BoxAverage avg = box_average(p, ps, box);
  EXPECT_EQ(avg.count, 64u);
  const double unit = 1 / (s * s);
  Mat3 want = Mat3::Zero();
  want(0, 0) = -Fx * unit, want(1, 1) = -Fy * unit, want(2, 2) = -Fz * unit, want(1, 0) = tau * unit;
  EXPECT_LT((avg.contact - want).norm(), kTol * want.norm()) << avg.contact;
  EXPECT_NEAR(avg.solid_fraction, std::numbers::pi / 6 * std::pow(2 * a / s, 3), 1e-15) << "64 spheres in 64 cells";
  // A profile along z through the same box: every slab of whole layers sees the same stress.
  const std::vector<BoxAverage> prof = stress_profile(p, ps, box, 2, 4);
  for (const BoxAverage& b : prof) EXPECT_LT((b.contact - want).norm(), kTol * want.norm());
}

// Kinetic part: two particles moving apart at +-v along x (mean velocity zero):
// sigma_k,xx = -(m v^2 + m v^2) / V over a box holding both; with a common drift added the
// fluctuations, hence the kinetic stress, are unchanged (to round-off of the drift).
TEST(LoveWeber, KineticPartFromVelocityFluctuations) {
  const double a = 1e-3, v = 0.2;
  for (double drift : {0.0, 1.5}) {
    Particles p;
    p.add(0, Vec3(0, 0, 0), a, 2500, 0);
    p.add(1, Vec3(0.01, 0, 0), a, 2500, 0);
    p.v[0] = Vec3(-v + drift, 0, drift);
    p.v[1] = Vec3(v + drift, 0, drift);
    const ParticleStress s = particle_stress(p, ContactForceSet{});
    const Box box{Vec3(-0.01, -0.01, -0.01), Vec3(0.02, 0.01, 0.01)};
    const BoxAverage avg = box_average(p, s, box);
    const double want = -2 * p.mass[0] * v * v / box.volume();
    EXPECT_NEAR(avg.kinetic(0, 0), want, 1e-12 * std::abs(want)) << "drift " << drift;
    EXPECT_NEAR(avg.kinetic(2, 2), 0.0, 1e-12 * std::abs(want)) << "drift " << drift;
    EXPECT_NEAR(avg.mean_velocity[2], drift, 1e-15);
    EXPECT_EQ(avg.contact, Mat3::Zero());
  }
}

// Deterministic for any thread count: the per-particle gather gives the same bits with 1 and 2
// threads.
TEST(LoveWeber, SameBitsForAnyThreadCount) {
  Particles p;
  ContactForceSet c;
  for (int k = 0; k < 2000; ++k) p.add(k, Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k)), 0.1 + 0.01 * (k % 5), 2500, 0);
  for (int k = 0; k + 7 < 2000; k += 3) {
    c.pair_i.push_back(k), c.pair_j.push_back(k + 7);
    c.pair_force.push_back(Vec3(std::sin(0.3 * k), std::cos(0.7 * k), 0.1));
    c.pair_normal.push_back(Vec3::UnitX()), c.pair_bonded.push_back(0);
  }
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const ParticleStress one = particle_stress(p, c);
  omp_set_num_threads(2);
  const ParticleStress two = particle_stress(p, c);
  omp_set_num_threads(before);
  for (std::size_t k = 0; k < p.size(); ++k) ASSERT_EQ(one.moment[k], two.moment[k]) << k;
}

}  // namespace
}  // namespace dem
