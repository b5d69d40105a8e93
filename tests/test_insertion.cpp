// Insertion over time ([[stage.insert]], generation/insertion.hpp): the rate kept, no overlap at
// insertion, ids after the largest present, and draws that depend on (seed, index) only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "generation/fill.hpp"
#include "generation/insertion.hpp"
#include "walls/wall.hpp"

#include "glass.hpp"

namespace dem {
namespace {

// A closed box of glass walls [0, 0.04] x [0, 0.04] x [0, 0.1], ten spheres on its floor.
Simulation glass_box(Vec3 gravity = Vec3(0, 0, -9.81)) {
  Simulation sim;
  sim.materials = glass_beads();
  sim.params.gravity = gravity;
  const Vec3 lo(0, 0, 0), hi(0.04, 0.04, 0.1);
  const char* names[3][2] = {{"box.xmin", "box.xmax"}, {"box.ymin", "box.ymax"}, {"box.zmin", "box.zmax"}};
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) sim.walls.push_back(Wall{names[axis][side], 0, box_face(lo, hi, axis, side == 1), {}});
  GenerationSpec g;
  g.box_min = lo;
  g.box_max = Vec3(0.04, 0.04, 0.01);
  g.count = 10;
  g.radius_min = g.radius_max = 0.002;
  g.material_fractions = {{0, 1.0}};
  std::mt19937_64 rng(3);
  fill_random(sim, g, rng);
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

InsertSpec pour(InsertSpec::Rate kind, double rate) {
  InsertSpec s;
  s.region.kind = Region::Kind::Box;
  s.region.min = Vec3(0.002, 0.002, 0.06);
  s.region.max = Vec3(0.038, 0.038, 0.095);
  s.material_fractions = {{0, 1.0}};
  s.radius_min = 0.0015;
  s.radius_max = 0.0025;
  s.rate_kind = kind;
  s.rate = rate;
  s.velocity = Vec3(0, 0, -1);
  s.end = s.total = std::numeric_limits<double>::infinity();
  s.seed = 11;
  return s;
}

// (1) The mass inserted by t is mass_rate x t within one particle (the definition of "due"), so
// within 2 % once the stage holds more than 50 particles: checked at 0.04 s of a 0.25 kg/s pour
// (about 10 g, particles of 35-160 mg), with the run stepping in between.
TEST(Insertion, MassRateKeptWithinTwoPercent) {
  Simulation sim = glass_box();
  const double rate = 0.25;
  std::vector<InsertGroup> groups{InsertGroup(pour(InsertSpec::Rate::Mass, rate), sim.materials)};
  const std::size_t before = sim.particles.size();
  const double t_end = 0.04;
  std::int64_t step = 0;
  while (sim.time < t_end) {
    insert_due(sim, groups, step++, sim.time);
    sim.advance();
  }
  double mass = 0;
  for (std::size_t k = before; k < sim.particles.size(); ++k) mass += sim.particles.mass[k];
  const double t_last = sim.time - sim.dt;  // the last event
  EXPECT_EQ(groups[0].deferred(), 0) << "the region had room";
  EXPECT_NEAR(mass, groups[0].placed_amount(), 1e-15);
  EXPECT_NEAR(mass / (rate * t_last), 1.0, 0.02) << mass << " kg in " << t_last << " s";
  EXPECT_GE(mass, rate * t_last) << "due: every particle whose predecessors' mass is within rate x t";
  EXPECT_LE(mass - rate * t_last, sphere_mass(2500, 0.0025)) << "within one particle";
  EXPECT_GT(sim.particles.size() - before, 50u);
}

// (2) A crowded region next to walls (no gravity: nothing leaves it): no new sphere overlaps a
// sphere or a wall at the moment it is inserted, by any amount (tolerance 1e-9 of its radius, for
// the round-off of the distance), and particles that find no room are deferred, not forced in.
// (3) Ids continue from the largest present (here 1000), one after another, all unique.
TEST(Insertion, NeverOverlapsAndIdsContinue) {
  Simulation sim = glass_box(Vec3::Zero());
  sim.particles.id[3] = 1000;
  InsertSpec s = pour(InsertSpec::Rate::Count, 40000);
  s.region.min = Vec3(-0.005, -0.005, 0.0);  // crosses the walls xmin, ymin and zmin
  s.region.max = Vec3(0.015, 0.015, 0.015);
  s.velocity = Vec3::Zero();
  std::vector<InsertGroup> groups{InsertGroup(s, sim.materials)};
  std::int64_t expect_id = 1001;
  for (std::int64_t step = 0; step < 60; ++step) {
    const std::size_t before = sim.particles.size();
    sim.step = step;  // a deferred particle tries new positions at the next step
    insert_due(sim, groups, step, step * 1e-4);
    const Particles& p = sim.particles;
    std::vector<WallGeometry> walls(sim.walls.size());
    for (std::size_t w = 0; w < walls.size(); ++w) place_wall(sim.walls[w], sim.time, sim.dt, walls[w]);
    for (std::size_t i = before; i < p.size(); ++i) {
      EXPECT_EQ(p.id[i], expect_id++);
      EXPECT_TRUE(sphere_in_region(s.region, p.x[i], p.radius[i]));
      for (std::size_t j = 0; j < p.size(); ++j)
        if (j != i) ASSERT_GE((p.x[i] - p.x[j]).norm() - (p.radius[i] + p.radius[j]), -1e-9 * p.radius[i]) << "ids " << p.id[i] << ", " << p.id[j];
      for (const WallGeometry& g : walls) ASSERT_GE((closest_point(g, p.x[i]) - p.x[i]).norm() - p.radius[i], -1e-9 * p.radius[i]);
    }
  }
  EXPECT_GT(groups[0].count(), 20) << "the region filled (random sequential addition jams near a solid fraction of 0.3)";
  EXPECT_GT(groups[0].deferred(), 0) << "and then deferred what found no room";
  std::set<Index> ids(sim.particles.id.begin(), sim.particles.id.end());
  EXPECT_EQ(ids.size(), sim.particles.size());
}

// What a group inserts depends on (seed, index) and the step only: a group rebuilt from its count
// (a resumed run) draws the same next particle and holds the same amount, to the bit; another seed
// draws other particles.
TEST(Insertion, DrawsDependOnSeedAndIndexOnly) {
  Simulation sim = glass_box();
  const InsertSpec s = pour(InsertSpec::Rate::Mass, 0.25);
  InsertGroup a(s, sim.materials);
  for (int k = 0; k < 37; ++k) a.placed(a.draw(a.count()));
  const InsertGroup b(s, sim.materials, 37, 0);
  EXPECT_EQ(a.placed_amount(), b.placed_amount());
  EXPECT_EQ(a.draw(37).radius, b.draw(37).radius);
  InsertSpec other = s;
  other.seed = 12;
  EXPECT_NE(InsertGroup(other, sim.materials).draw(0).radius, a.draw(0).radius);
  // Two identical simulations insert identical particles.
  Simulation u = glass_box(), v = glass_box();
  std::vector<InsertGroup> gu{InsertGroup(s, u.materials)}, gv{InsertGroup(s, v.materials)};
  insert_due(u, gu, 0, 0.01);
  insert_due(v, gv, 0, 0.01);
  ASSERT_EQ(u.particles.size(), v.particles.size());
  EXPECT_EQ(u.particles.x, v.particles.x);
  EXPECT_EQ(u.particles.radius, v.particles.radius);
}

// The window and the cap: nothing before `start`, nothing new due after `end`, never more than
// total_count.
TEST(Insertion, WindowAndTotal) {
  Simulation sim = glass_box(Vec3::Zero());
  InsertSpec s = pour(InsertSpec::Rate::Count, 1000);
  s.start = 0.01;
  s.end = 0.0305;
  std::vector<InsertGroup> g{InsertGroup(s, sim.materials)};
  insert_due(sim, g, 0, 0.005);
  EXPECT_EQ(g[0].count(), 0);
  insert_due(sim, g, 1, 0.0205);
  EXPECT_EQ(g[0].count(), 11) << "particles 0..10 are due at 0.01 s after start";
  insert_due(sim, g, 2, 0.5);
  EXPECT_EQ(g[0].count(), 21) << "up to end only";
  s.end = std::numeric_limits<double>::infinity();
  s.total = 5;
  std::vector<InsertGroup> capped{InsertGroup(s, sim.materials)};
  insert_due(sim, capped, 0, 0.5);
  EXPECT_EQ(capped[0].count(), 5);
}

}  // namespace
}  // namespace dem
