// The linked-cell search must find exactly the overlapping pairs that an O(N^2) check finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "search/linked_cells.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

std::vector<FoundContact> brute_force(const Particles& p) {
  std::vector<FoundContact> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double r = p.radius[i] + p.radius[j];
      if ((p.x[i] - p.x[j]).squaredNorm() < r * r)
        out.push_back({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]), int(i), int(j)});
    }
  std::sort(out.begin(), out.end());
  return out;
}

class SearchMatchesBruteForce : public ::testing::TestWithParam<int> {};

TEST_P(SearchMatchesBruteForce, PolydisperseRandomCloud) {
  std::mt19937_64 rng(GetParam());
  std::uniform_real_distribution<double> u(0, 1);
  Particles p;
  // Size ratio 10 (as in the sand-production case), dense enough for many overlaps; ids shuffled
  // so that id order differs from storage order.
  const int n = 1500;
  std::vector<Index> ids(n);
  for (int k = 0; k < n; ++k) ids[k] = 1000 + 3 * k;
  std::shuffle(ids.begin(), ids.end(), rng);
  for (int k = 0; k < n; ++k) p.add(ids[k], Vec3(u(rng), u(rng), 0.3 * u(rng)), 0.002 + 0.018 * u(rng), 1000, 0);
  // A far-away particle stretches the bounding box (tests the grid-size cap).
  p.add(5, Vec3(50, -20, 3), 0.01, 1000, 0);
  std::vector<FoundContact> fast;
  LinkedCells cells;
  cells.find_near_pairs(p, fast);
  for (const FoundContact& c : fast) EXPECT_LT(c.key_i, c.key_j);
  std::sort(fast.begin(), fast.end());
  const std::vector<FoundContact> slow = brute_force(p);
  ASSERT_GT(slow.size(), 100u);
  ASSERT_EQ(fast.size(), slow.size());
  for (std::size_t k = 0; k < fast.size(); ++k) {
    EXPECT_EQ(fast[k].key_i, slow[k].key_i);
    EXPECT_EQ(fast[k].key_j, slow[k].key_j);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SearchMatchesBruteForce, ::testing::Values(1, 2, 3));

// Along a trajectory (the neighbour list is reused between rebuilds, with a skin), the contacts of
// every step are exactly the overlapping pairs and particle-wall overlaps an O(N^2) check finds,
// with a polydisperse cloud (size ratio 10) moving fast in a box whose lid moves down.
TEST(NeighbourList, ContactsEqualBruteForceEveryStep) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  Simulation sim;
  Material m;
  m.name = "m";
  m.kn = m.kt = 1e3;
  m.restitution = 0.9;
  sim.materials = MaterialTable({m}, {});
  const double L = 0.05;
  sim.walls.push_back(Wall{"floor", 0, {Vec3(0, 0, 0), Vec3(L, 0, 0), Vec3(L, L, 0), Vec3(0, L, 0)}, {}});
  Wall lid{"lid", 0, {Vec3(0, 0, L), Vec3(L, 0, L), Vec3(L, L, L), Vec3(0, L, L)}, {}};
  lid.motion.velocity = Vec3(0, 0, -0.2);
  sim.walls.push_back(lid);
  for (int k = 0; k < 300; ++k) {
    const double a = 0.0005 + 0.0045 * u(rng);
    sim.particles.add(k, Vec3(a + (L - 2 * a) * u(rng), a + (L - 2 * a) * u(rng), a + (L - 2 * a) * u(rng)), a, 2500, 0);
    sim.particles.v[k] = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  sim.dt = 0.1 * sim.critical_time_step();
  sim.params.max_overlap = 10;  // random placement overlaps deeply; this test is about the search
  std::size_t pair_contacts = 0, wall_contacts = 0;
  for (int s = 0; s < 400; ++s) {
    // The contacts of a step are found at the positions before it: brute force on those.
    const std::vector<FoundContact> pairs = brute_force(sim.particles);
    std::vector<std::pair<Index, Index>> walls;
    for (std::size_t k = 0; k < sim.particles.size(); ++k)
      for (std::size_t w = 0; w < sim.walls.size(); ++w) {
        const std::vector<Vec3> v = sim.walls[w].vertices_at(sim.time);
        const Vec3 c = closest_point_on_polygon(v.data(), 4, Vec3::UnitZ(), sim.particles.x[k]);
        if ((c - sim.particles.x[k]).norm() < sim.particles.radius[k]) walls.emplace_back(sim.particles.id[k], static_cast<Index>(w));
      }
    std::sort(walls.begin(), walls.end());
    sim.advance();
    ASSERT_EQ(sim.pair_contacts().size(), pairs.size()) << "step " << s;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      ASSERT_EQ(sim.pair_contacts().key_i[k], pairs[k].key_i);
      ASSERT_EQ(sim.pair_contacts().key_j[k], pairs[k].key_j);
    }
    ASSERT_EQ(sim.wall_contacts().size(), walls.size()) << "step " << s;
    for (std::size_t k = 0; k < walls.size(); ++k) {
      ASSERT_EQ(sim.wall_contacts().key_i[k], walls[k].first);
      ASSERT_EQ(sim.wall_contacts().key_j[k], walls[k].second);
    }
    pair_contacts += pairs.size();
    wall_contacts += walls.size();
  }
  EXPECT_GT(pair_contacts, 1000u) << "the trajectory must exercise contacts";
  EXPECT_GT(wall_contacts, 100u);
  EXPECT_GT(sim.neighbour_builds(), 3) << "and several list rebuilds";
  EXPECT_LT(sim.neighbour_builds(), 300) << "the list is reused between rebuilds";
}

}  // namespace
}  // namespace dem
