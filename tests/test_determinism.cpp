// The same inputs give the same bits for any thread count (forces are summed per particle in a
// fixed order, DESIGN.md).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <numeric>
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
  // memcmp must not see the null data() of empty vectors (UBSan), even for a length of 0.
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
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

// Storage order is speed only (SimParams::sort_every): a cloud stored in shuffled order and sorted
// along the cells every 7 steps ends with the same bits, particle by particle (matched by id), as
// the same cloud never sorted, with one and with two threads. The positions are compared after
// putting both in id order.
TEST(Determinism, StorageOrderChangesNoBit) {
  auto by_id = [](const Simulation& s, const std::vector<Vec3>& field) {
    std::vector<std::size_t> k(s.particles.size());
    std::iota(k.begin(), k.end(), 0);
    std::sort(k.begin(), k.end(), [&](std::size_t a, std::size_t b) { return s.particles.id[a] < s.particles.id[b]; });
    std::vector<Vec3> out;
    for (std::size_t j : k) out.push_back(field[j]);
    return out;
  };
  Simulation plain = make_cloud();
  plain.params.sort_every = 0;
  omp_set_num_threads(1);
  for (int s = 0; s < 1500; ++s) plain.advance();
  for (int threads : {1, 2}) {
    Simulation sorted = make_cloud();
    std::vector<std::size_t> order(sorted.particles.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(5));
    sorted.particles.reorder(order);
    sorted.params.sort_every = 7;
    sorted.params.sort_min_particles = 0;
    omp_set_num_threads(threads);
    for (int s = 0; s < 1500; ++s) sorted.advance();
    ASSERT_NE(sorted.particles.id, plain.particles.id) << "the storage orders must differ for the test to mean anything";
    EXPECT_TRUE(same_bits(by_id(plain, plain.particles.x), by_id(sorted, sorted.particles.x))) << threads << " thread(s)";
    EXPECT_TRUE(same_bits(by_id(plain, plain.particles.v), by_id(sorted, sorted.particles.v))) << threads << " thread(s)";
    EXPECT_TRUE(same_bits(by_id(plain, plain.particles.w), by_id(sorted, sorted.particles.w))) << threads << " thread(s)";
    // The contact lists are keyed by ids: the same keys and springs in the same order. (This
    // cloud has pair contacts at the end but none with the walls, so only pairs are compared.)
    ASSERT_GT(plain.pair_contacts().size(), 0u) << "the test must exercise contacts";
    EXPECT_EQ(plain.pair_contacts().key_i, sorted.pair_contacts().key_i);
    EXPECT_EQ(plain.pair_contacts().key_j, sorted.pair_contacts().key_j);
    EXPECT_TRUE(same_bits(plain.pair_contacts().spring, sorted.pair_contacts().spring));
  }
}

}  // namespace
}  // namespace dem
