// The health figures of sim/health.hpp against states known by hand: a simple cubic lattice of
// n^3 spheres overlapping each neighbour by u, standing on a floor it overlaps by u_w. Its contacts
// are counted exactly (3 n^2 (n - 1) pairs, n^2 wall contacts), its coordination number is
// 2 x 3 (n - 1) / n, its elastic energy is ½ k u² per contact and the floor carries n² k u_w. The
// figures are taken after one step of 1e-7 s, which moves a sphere by about 1e-9 of the overlap:
// tolerances 1e-6 relative. Kinetic energy: spheres given v and ω, ½ m v² and ½ I ω² per sphere
// (1e-12 relative), the same bits on one thread and on two.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "run/health_log.hpp"
#include "sim/health.hpp"

namespace dem {
namespace {

constexpr int kN = 4;
constexpr double kA = 0.01, kU = 2e-5, kUw = 1e-5;

Simulation lattice_on_floor() {
  Simulation sim;
  Material m;
  m.name = "glass";
  m.density = 2000;
  m.kn = m.kt = 1e5;
  // Undamped: the normal dashpot acts on the overlap's change over the coming step (the lattice
  // starts to spring apart), and the checks below are of the elastic state alone.
  m.restitution = m.restitution_t = 1;
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3::Zero();
  const double L = 1;
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-L, -L, 0), Vec3(L, -L, 0), Vec3(L, L, 0), Vec3(-L, L, 0)}, {}});
  const double s = 2 * kA - kU;
  int id = 0;
  for (int k = 0; k < kN; ++k)
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) sim.particles.add(id++, Vec3(i * s, j * s, kA - kUw + k * s), kA, m.density, 0);
  sim.dt = 1e-7;
  return sim;
}

TEST(Health, LatticeOnAFloorGivesItsContactsCoordinationOverlapAndElasticEnergy) {
  Simulation sim = lattice_on_floor();
  sim.advance();
  const Health h = measure_health(sim);
  const std::size_t pairs = 3 * kN * kN * (kN - 1), floor = kN * kN;
  EXPECT_EQ(h.particles, static_cast<std::size_t>(kN * kN * kN));
  EXPECT_EQ(h.pair_contacts, pairs);
  EXPECT_EQ(h.wall_contacts, floor);
  EXPECT_DOUBLE_EQ(h.coordination, 2.0 * 3 * (kN - 1) / kN);  // 4.5: the floor does not count
  EXPECT_NEAR(h.max_overlap_ratio, kU / kA, 1e-6 * kU / kA);
  const double k = sim.materials.pair(0, 0).kn;
  const double elastic = pairs * 0.5 * k * kU * kU + floor * 0.5 * k * kUw * kUw;
  EXPECT_NEAR(h.elastic_bound, elastic, 1e-6 * elastic);
  ASSERT_EQ(h.wall_loads.size(), 1u);
  EXPECT_NEAR(h.wall_loads[0].force.z(), -(floor * k * kUw), 1e-6 * floor * k * kUw);  // pressed down
  EXPECT_EQ(h.bonds, 0u);
  EXPECT_EQ(intact_bonds(sim), 0u);
  sim.bond_present_contacts(true);
  EXPECT_EQ(intact_bonds(sim), pairs + floor);
}

TEST(Health, KineticEnergyIsHalfMVSquaredAndHalfIOmegaSquaredWithTheSameBitsOnAnyThreadCount) {
  Simulation sim;
  Material m;
  m.name = "glass";
  m.density = 2500;
  m.kn = m.kt = 1e5;
  sim.materials = MaterialTable({m}, {});
  double translation = 0, rotation = 0;
  for (int q = 0; q < 3000; ++q) {  // three blocks of the parallel sum, apart from each other
    const double a = 0.001 * (1 + q % 7);
    sim.particles.add(q, Vec3(0.02 * (q % 50), 0.02 * (q / 50), 0), a, m.density, 0);
    const Vec3 v(std::sin(q), std::cos(q), 0.1 * q / 3000.0), w(0, 3.0 * (q % 5), -1);
    sim.particles.v[q] = v, sim.particles.w[q] = w;
    const double mass = sphere_mass(m.density, a);
    translation += 0.5 * mass * v.squaredNorm();
    rotation += 0.5 * 0.4 * mass * a * a * w.squaredNorm();
  }
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Health one = measure_health(sim);
  omp_set_num_threads(2);
  const Health two = measure_health(sim);
  omp_set_num_threads(threads);
  EXPECT_NEAR(one.kinetic_translation, translation, 1e-12 * translation);
  EXPECT_NEAR(one.kinetic_rotation, rotation, 1e-12 * rotation);
  EXPECT_EQ(one.kinetic_translation, two.kinetic_translation);
  EXPECT_EQ(one.kinetic_rotation, two.kinetic_rotation);
  EXPECT_EQ(one.pair_contacts, 0u);
  EXPECT_EQ(one.coordination, 0.0);
}

// The interval between rows: --health-every (steps) over the scene's health_every (seconds, at
// least one step) over the default, a hundredth of the stage but never under 500 steps: both
// sides of that floor, at step counts users run.
TEST(Health, IntervalTakesTheCommandLineThenTheSceneThenAHundredthOfTheStageButAtLeast500Steps) {
  EXPECT_EQ(health_interval({}, {}, 2.9, 3.7e-6), 7838) << "a long stage: 783,784 steps / 100";
  EXPECT_EQ(health_interval({}, {}, 0.01, 1e-5), kMinDefaultHealthEvery) << "1,000 steps / 100 = 10, under the floor";
  EXPECT_EQ(health_interval({}, seconds(0.004), 0.01, 1e-5), 400) << "the scene's 0.004 s";
  EXPECT_EQ(health_interval({}, seconds(1e-9), 0.01, 1e-5), 1) << "at least one step";
  EXPECT_EQ(health_interval(steps(250), seconds(0.004), 0.01, 1e-5), 250) << "the command line wins";
}

}  // namespace
}  // namespace dem
