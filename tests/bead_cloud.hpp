#pragma once
// A cloud of 200 glass beads (friction 25°) moving at random in a closed 0.02 × 0.02 × 0.04 m box:
// the scene of the bit-for-bit tests (thread counts, storage orders, restarts). No time step set.
#include <random>

#include "draw_vec.hpp"
#include "generation/fill.hpp"
#include "glass.hpp"
#include "sim/simulation.hpp"

namespace dem {

inline Simulation bead_cloud() {
  Simulation sim;
  sim.materials = glass_beads(25);
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
  for (Vec3& v : sim.particles.v) v = draw_vec(u, rng);
  return sim;
}

}  // namespace dem
