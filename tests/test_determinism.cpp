// The same inputs give the same bits for any thread count (forces are summed per particle in a
// fixed order, DESIGN.md).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>

#include "generation/fill.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

Simulation make_cloud() {
  Simulation sim;
  Material m;
  m.name = "glass";
  m.density = 2500;
  m.kn = m.kt = 5e4;
  m.friction_angle = 25;
  m.restitution = 0.3;
  sim.materials = MaterialTable({m}, {});
  const double L = 0.02;
  const Vec3 lo(0, 0, 0), hi(L, L, 2 * L);
  // Six walls of a closed box.
  for (int axis = 0; axis < 3; ++axis)
    for (bool side : {false, true}) sim.walls.push_back(Wall{"w", 0, box_face(lo, hi, axis, side), {}});
  GenerationSpec g;
  g.box_min = lo;
  g.box_max = hi;
  g.count = 200;
  g.radius_min = 0.0012;
  g.radius_max = 0.0018;
  g.material_fractions = {{0, 1.0}};
  std::mt19937_64 rng(3);
  fill_random(sim, g, rng);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Vec3& v : sim.particles.v) v = Vec3(u(rng), u(rng), u(rng));
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Determinism, OneAndTwoThreadsGiveTheSameBits) {
  Simulation a = make_cloud(), b = make_cloud();
  omp_set_num_threads(1);
  for (int s = 0; s < 1500; ++s) a.advance();
  omp_set_num_threads(2);
  for (int s = 0; s < 1500; ++s) b.advance();
  ASSERT_GT(a.pair_contacts().size(), 0u) << "the test must exercise contacts";
  EXPECT_TRUE(same_bits(a.particles.x, b.particles.x));
  EXPECT_TRUE(same_bits(a.particles.v, b.particles.v));
  EXPECT_TRUE(same_bits(a.particles.w, b.particles.w));
  EXPECT_TRUE(same_bits(a.pair_contacts().spring, b.pair_contacts().spring));
}

}  // namespace
}  // namespace dem
