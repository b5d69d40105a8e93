// Random primary sets (SPEC §9): spheres given by [[generation.place]] come first with their ids,
// and no random sphere overlaps any other sphere, given or random.
#include <gtest/gtest.h>

#include <random>

#include "generation/fill.hpp"
#include "sim/simulation.hpp"

#include "glass.hpp"

namespace dem {
namespace {

Simulation with_glass() {
  Simulation sim;
  sim.materials = glass_beads();
  return sim;
}

GenerationSpec intruder_box() {
  GenerationSpec g;
  g.box_min = Vec3(0, 0, 0);
  g.box_max = Vec3(0.04, 0.04, 0.08);
  g.count = 600;
  g.radius_min = g.radius_max = 0.002;
  g.material_fractions = {{0, 1.0}};
  // A sphere three times larger near the floor, as in the segregation case (SPEC §12), and a second one.
  g.placed = {PlacedSphere{Vec3(0.02, 0.02, 0.0065), 0.006, 0}, PlacedSphere{Vec3(0.01, 0.03, 0.05), 0.004, 0}};
  return g;
}

TEST(Generation, PlacedSpheresComeFirstAndNothingOverlaps) {
  Simulation sim = with_glass();
  const GenerationSpec g = intruder_box();
  std::mt19937_64 rng(7);
  fill_random(sim, g, rng);
  const Particles& p = sim.particles;
  ASSERT_EQ(p.size(), 602u);
  for (std::size_t k = 0; k < g.placed.size(); ++k) {
    EXPECT_EQ(p.id[k], static_cast<Index>(k));
    EXPECT_EQ(p.x[k], g.placed[k].centre);
    EXPECT_EQ(p.radius[k], g.placed[k].radius);
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.id[i], static_cast<Index>(i)) << "ids 0..N-1 in order";
    for (int d = 0; d < 3; ++d) {
      EXPECT_GE(p.x[i][d] - p.radius[i], g.box_min[d]);
      EXPECT_LE(p.x[i][d] + p.radius[i], g.box_max[d]);
    }
    // Brute force over all pairs: the exact answer, independent of the generator's grid.
    for (std::size_t j = i + 1; j < p.size(); ++j)
      ASSERT_GE((p.x[i] - p.x[j]).norm(), p.radius[i] + p.radius[j]) << "spheres " << i << " and " << j << " overlap";
  }
  // The region around the large sphere is not left empty: random spheres touch its neighbourhood.
  int near = 0;
  for (std::size_t i = 2; i < p.size(); ++i) near += (p.x[i] - p.x[0]).norm() < p.radius[0] + 3 * p.radius[i];
  EXPECT_GT(near, 0);
}

TEST(Generation, SameSeedSameSpheres) {
  Simulation a = with_glass(), b = with_glass();
  std::mt19937_64 ra(11), rb(11);
  fill_random(a, intruder_box(), ra);
  fill_random(b, intruder_box(), rb);
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.radius, b.particles.radius);
}

}  // namespace
}  // namespace dem
