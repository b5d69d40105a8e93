#pragma once
// A scaling scene whose physics per sphere does not depend on N: spheres of the chute's material
// (bench/chute_scene.hpp: diameter 1, kn = 2e5, friction 0.5, dt = 1e-4, skin 0.1) on a simple
// cubic lattice of spacing 0.99, pressed together in a box periodic along all three axes, without
// gravity, with random velocities of up to 0.05 per component. Every sphere holds its 6 contacts
// (overlap 0.01; the velocities move a sphere by about 1e-4 against its neighbours) and 3 pair
// candidates (the diagonal neighbours lie beyond the skin) at any N, so the cost per
// particle-step against N shows the code's own growth (caches, memory), not the scene's.
#include <algorithm>
#include <cmath>
#include <random>

#include "chute_scene.hpp"  // chute_materials
#include "sim/simulation.hpp"

namespace dem::bench {

constexpr double kLatticeSpacing = 0.99;

// About n spheres: a cube of side round(cbrt(n)) (at least 4).
inline Simulation lattice_scene(long n) {
  const int side = std::max(4, static_cast<int>(std::lround(std::cbrt(static_cast<double>(n)))));
  Simulation sim;
  sim.materials = chute_materials();
  sim.params.gravity = Vec3::Zero();
  sim.params.skin = 0.1;
  sim.dt = 1e-4;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> vel(-0.05, 0.05);
  Index id = 0;
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        sim.particles.add(id, kLatticeSpacing * Vec3(i + 0.5, j + 0.5, k + 0.5), 0.5, 1, 0);
        sim.particles.v[id++] = Vec3(vel(rng), vel(rng), vel(rng));
      }
  PeriodicBox box;
  box.axis = {true, true, true};
  box.hi = Vec3::Constant(kLatticeSpacing * side);
  sim.set_periodic(box);
  return sim;
}

}  // namespace dem::bench
