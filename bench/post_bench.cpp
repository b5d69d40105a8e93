// Builds the checkpoints of the post-macro benchmark (bench/run_post_bench.sh): N spheres of
// radius 1 mm (rho 2500) on a simple cubic lattice of spacing 1.998 mm (every neighbour pair
// overlapping by 2 um: 3 N contacts), jittered by up to 0.2 um, with random velocities up to
// 0.01 m/s per component, in a closed box of six walls each pressing the outer layer by 1 um;
// kn = 1e4 N/m, friction 0.5. The current state (post_cur.h5) and a reference (post_ref.h5) whose
// positions are the current ones minus an affine displacement (E x + c, |E| ~ 1e-3), without every
// 10th particle (matched by id, so "new" for the displacement). The scene text is empty: post-macro
// uses the stored materials.
// Usage: post_bench N DIR
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "io/checkpoint.hpp"
#include "sim/simulation.hpp"

int main(int argc, char** argv) {
  using namespace dem;
  if (argc != 3) {
    std::fprintf(stderr, "usage: post_bench N DIR\n");
    return 2;
  }
  const long n = std::atol(argv[1]);
  const std::string dir = argv[2];
  const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n)) - 1e-9));
  const double a = 1e-3, s = 2 * a - 2e-6;
  Material bead;
  bead.name = "bead";
  bead.density = 2500;
  bead.kn = bead.kt = 1e4;
  bead.friction_angle = std::atan(0.5) * 180 / M_PI;
  bead.restitution = bead.restitution_t = 0.5;
  Simulation sim;
  sim.materials = MaterialTable({bead}, {});
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(-1, 1);
  long placed = 0;
  for (int k = 0; k < side && placed < n; ++k)
    for (int j = 0; j < side && placed < n; ++j)
      for (int i = 0; i < side && placed < n; ++i, ++placed) {
        sim.particles.add(placed, Vec3(i, j, k) * s + 2e-7 * Vec3(U(rng), U(rng), U(rng)), a, bead.density, 0);
        sim.particles.v.back() = 0.01 * Vec3(U(rng), U(rng), U(rng));
      }
  const Vec3 lo = Vec3::Constant(-a + 1e-6), hi = Vec3::Constant((side - 1) * s + a - 1e-6);
  for (int axis = 0; axis < 3; ++axis)
    for (bool max_side : {false, true})
      sim.walls.push_back(Wall{std::string("box.") + "xyz"[axis] + (max_side ? "max" : "min"), 0, box_face(lo, hi, axis, max_side), {}});
  sim.dt = 0.1 * sim.critical_time_step();
  CheckpointMeta meta;
  meta.writer = "post_bench";
  meta.run.stage = "post_bench";
  write_checkpoint(dir + "/post_cur.h5", sim, meta);

  Eigen::Matrix3d E;
  E << 1e-3, 2e-4, 0, -3e-4, -2e-3, 1e-4, 0, 5e-4, 1.5e-3;
  const Vec3 c(1e-4, -2e-4, 3e-4);
  std::vector<bool> keep(sim.particles.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    sim.particles.x[k] -= E * sim.particles.x[k] + c;
    keep[k] = k % 10 != 0;
  }
  sim.particles.keep_only(keep);
  write_checkpoint(dir + "/post_ref.h5", sim, meta);
  std::printf("post_bench: %ld particles on a %d^3 lattice, box %.4f m: %s/post_cur.h5, %s/post_ref.h5\n", placed, side, hi[0] - lo[0],
              dir.c_str(), dir.c_str());
  return 0;
}
