// The sink ([stage.sink], generation/sink.hpp): particles removed where their centre enters a
// region, counted with their mass, against free fall in closed form; events only every `every`
// steps; the mass total the same bits in any storage order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "generation/sink.hpp"

#include "glass.hpp"

namespace dem {
namespace {

// Spheres of radius a at rest, apart in x (they never touch), their centres at heights h_k.
Simulation falling_column(const std::vector<double>& heights, double a) {
  Simulation sim;
  sim.materials = glass_beads();
  sim.params.gravity = Vec3(0, 0, -9.81);
  for (std::size_t k = 0; k < heights.size(); ++k)
    sim.particles.add(static_cast<Index>(k), Vec3(4 * a * static_cast<double>(k), 0, heights[k]), a, 2500, 0);
  sim.dt = 1e-4;
  return sim;
}

SinkSpec floor_sink() {
  SinkSpec s;
  s.region.kind = Region::Kind::HalfSpace;
  s.region.point = Vec3::Zero();
  s.region.normal = Vec3(0, 0, -1);  // z <= 0
  return s;
}

// A sphere dropped from rest at height h reaches z = 0 at t = sqrt(2 h / g) (free fall). After T =
// 0.2 s the sink has removed exactly those with sqrt(2 h / g) <= T, i.e. h <= g T^2 / 2 = 0.196 m;
// the heights are at least 0.01 m (about 10 steps of fall at that speed) from it, so the
// integrator's O(dt) error in the arrival time cannot move one across. The mass is n rho 4/3 pi a^3.
TEST(Sink, RemovesWhatFreeFallBringsIntoTheRegion) {
  const double a = 0.001;
  const std::vector<double> heights{0.05, 0.30, 0.10, 0.185, 0.25, 0.0005, 0.21, 0.15};
  Simulation sim = falling_column(heights, a);
  const SinkSpec sink = floor_sink();
  SinkTotals totals;
  std::int64_t step = 0;
  const double T = 0.2;
  while (sim.time < T - 1e-12) {
    sim.advance();
    sink_due(sim, sink, ++step, totals);
  }
  const double reach = 9.81 * T * T / 2;
  std::int64_t expected = 0;
  for (double h : heights) expected += h <= reach;
  EXPECT_EQ(totals.count, expected);
  EXPECT_EQ(static_cast<std::int64_t>(sim.particles.size()), static_cast<std::int64_t>(heights.size()) - expected);
  EXPECT_NEAR(totals.mass, static_cast<double>(expected) * sphere_mass(2500, a), 1e-15);
  for (std::size_t k = 0; k < sim.particles.size(); ++k) EXPECT_GT(sim.particles.x[k].z(), 0) << "a particle below the floor was kept";
}

// An event only at multiples of `every`: in between, a particle in the region stays.
TEST(Sink, ActsOnlyEveryNSteps) {
  Simulation sim = falling_column({-0.01, 0.5}, 0.001);
  SinkSpec sink = floor_sink();
  sink.every = 10;
  SinkTotals totals;
  for (std::int64_t step = 1; step < 10; ++step) EXPECT_EQ(sink_due(sim, sink, step, totals), 0u);
  EXPECT_EQ(totals.count, 0);
  EXPECT_EQ(sink_due(sim, sink, 10, totals), 1u);
  EXPECT_EQ(totals.count, 1);
  EXPECT_EQ(sim.particles.size(), 1u);
  EXPECT_EQ(sim.particles.id[0], 1);
}

// The mass is summed in id order: the same bits whatever the storage order (radii of many sizes,
// so that another order of the sum would change its last bits).
TEST(Sink, MassTotalIndependentOfStorageOrder) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0005, 0.002);
  Simulation base;
  base.materials = glass_beads();
  for (int k = 0; k < 200; ++k) base.particles.add(k, Vec3(0.01 * k, 0, k % 3 == 0 ? -0.01 : 0.01), u(rng), 2500, 0);
  const SinkSpec sink = floor_sink();
  SinkTotals sorted;
  Simulation a = base;
  sink_due(a, sink, 0, sorted);
  std::vector<std::size_t> order(base.particles.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = order.size() - 1 - k;
  std::shuffle(order.begin(), order.end(), rng);
  Simulation b = base;
  b.particles.reorder(order);
  SinkTotals shuffled;
  sink_due(b, sink, 0, shuffled);
  EXPECT_EQ(sorted.count, 67);
  EXPECT_EQ(shuffled.count, sorted.count);
  EXPECT_EQ(std::memcmp(&shuffled.mass, &sorted.mass, sizeof(double)), 0) << shuffled.mass << " vs " << sorted.mass;
}

}  // namespace
}  // namespace dem
