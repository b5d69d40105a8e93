// The settle benchmark for our code (bench/run_peer_bench.sh runs it beside LAMMPS and LIGGGHTS):
//   settle_bench run N STEPS THREADS [MODEL]
//                                         runs the scene of bench/settle_scene.hpp for STEPS steps and
//                                         prints one line: N, steps, threads, loop seconds,
//                                         particle-steps per second, contacts, kinetic energies,
//                                         peak resident memory; MODEL linear (default), hertz,
//                                         hertz-rolling, or either with -explicit (the explicit
//                                         dashpot) (settle_scene.hpp, hertz_models.hpp)
//   settle_bench mesh N STEPS THREADS T   the same with the floor made of about T triangles (a
//                                         rectangle mesh, as an STL floor would be): the price of a
//                                         fine mesh wall against one plane
//   settle_bench shuffled N STEPS THREADS SORT_EVERY
//                                         the same with the storage order shuffled (as random
//                                         placement leaves it) and re-sorted along the cells every
//                                         SORT_EVERY steps (0 = never): the price of poor locality
//   settle_bench series N STEPS EVERY SEED MODEL [FRICTION ROLLING_FRICTION]
//                                         the side-by-side check with LIGGGHTS (bench/peers/
//                                         run_side_by_side.sh): the scene with initial velocities
//                                         drawn from SEED, one thread, a CSV row every EVERY steps:
//                                         step, time, translational and rotational kinetic energy,
//                                         mean coordination 2 x pair contacts / N (walls not
//                                         counted, as LIGGGHTS's compute contact/atom); a Hertz
//                                         MODEL, its friction and rolling friction optionally changed
//   settle_bench lammps-data N FILE [SEED]
//                                         writes the same initial state as a LAMMPS data file
// The loop time covers the steps only (scene construction excluded), as LAMMPS's "Loop time".
#include <omp.h>

#include <chrono>
#include <cmath>
#include <string>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <numeric>
#include <random>
#include <algorithm>

#include "bench_report.hpp"
#include "settle_scene.hpp"
#include "walls/primitives.hpp"

using namespace dem;

namespace {

using bench::peak_rss_kb;

int run(long n, long steps, int threads, long floor_triangles = 0, long shuffled_sort_every = -1,
        bench::ContactModel model = bench::ContactModel::Linear) {
  omp_set_num_threads(threads);
  const long rss_before = peak_rss_kb();
  Simulation sim = bench::settle_scene(bench::settle_size(n), 0.5, true, model);
  if (shuffled_sort_every >= 0) {
    std::vector<std::size_t> order(sim.particles.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(7));
    sim.particles.reorder(order);
    sim.params.sort_every = shuffled_sort_every;
    sim.params.sort_min_particles = 0;
  }
  if (floor_triangles > 0) {
    // Wall 4 is the floor (box_face axis 2, min side): replace it by a mesh of the same rectangle.
    const std::vector<Vec3> f = sim.walls[4].base;
    const int cells = std::max(1, static_cast<int>(std::lround(std::sqrt(floor_triangles / 2.0))));
    sim.walls.erase(sim.walls.begin() + 4);
    for (const std::vector<Vec3>& t : rectangle_mesh(f[0], f[1] - f[0], f[3] - f[0], cells, cells, true))
      sim.walls.push_back(Wall{"floor." + std::to_string(sim.walls.size()), 1, t, {}});
  }
  bench::timed_run(sim, steps, threads, rss_before);
  return 0;
}

// The `series` mode above: what run_side_by_side.sh compares with LIGGGHTS's thermo output.
int series(long n, long steps, long every, std::uint64_t seed, bench::ContactModel model, bench::HertzBead bead) {
  omp_set_num_threads(1);
  Simulation sim = bench::settle_scene(bench::settle_size(n), 0.5, true, model, seed, bead);
  sim.params.keep_pair_results = false;
  std::printf("step,time_s,ke_J,rke_J,coordination\n");
  for (long s = 0;; ++s) {
    if (s % every == 0 || s == steps) {
      const double rke = bench::rotational_energy(sim);
      std::printf("%ld,%.9g,%.10g,%.10g,%.6f\n", s, s * sim.dt, sim.kinetic_energy() - rke, rke,
                  2.0 * static_cast<double>(sim.pair_contact_count()) / static_cast<double>(sim.particles.size()));
    }
    if (s == steps) return 0;
    sim.advance();
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if ((argc == 5 || argc == 6) && std::strcmp(argv[1], "run") == 0)
      return run(std::atol(argv[2]), std::atol(argv[3]), std::atoi(argv[4]), 0, -1,
                 bench::contact_model_named(argc == 6 ? argv[5] : "linear"));
    if (argc == 6 && std::strcmp(argv[1], "mesh") == 0)
      return run(std::atol(argv[2]), std::atol(argv[3]), std::atoi(argv[4]), std::atol(argv[5]));
    if (argc == 6 && std::strcmp(argv[1], "shuffled") == 0)
      return run(std::atol(argv[2]), std::atol(argv[3]), std::atoi(argv[4]), 0, std::atol(argv[5]));
    if ((argc == 7 || argc == 9) && std::strcmp(argv[1], "series") == 0) {
      bench::HertzBead bead = bench::kSettleHertz;
      if (argc == 9) {
        bead.friction = std::atof(argv[7]);
        bead.rolling_friction = std::atof(argv[8]);
      }
      const bench::ContactModel model = bench::contact_model_named(argv[6]);
      if (model == bench::ContactModel::Linear) throw std::invalid_argument("series: the model must be hertz or hertz-rolling, with or without -explicit");
      return series(std::atol(argv[2]), std::atol(argv[3]), std::max(1L, std::atol(argv[4])), std::strtoull(argv[5], nullptr, 10), model, bead);
    }
    if ((argc == 4 || argc == 5) && std::strcmp(argv[1], "lammps-data") == 0) {
      const long n = std::atol(argv[2]);
      const bench::LatticeSize size = bench::settle_size(n);
      const std::uint64_t seed = argc == 5 ? std::strtoull(argv[4], nullptr, 10) : 12345;
      bench::write_lammps_data(bench::settle_scene(size, 0.5, true, bench::ContactModel::Linear, seed), size, argv[3]);
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "settle_bench: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: settle_bench run N STEPS THREADS [linear|hertz|hertz-rolling|hertz-explicit|hertz-rolling-explicit] | settle_bench mesh N STEPS THREADS TRIANGLES | "
                       "settle_bench series N STEPS EVERY SEED hertz|hertz-rolling[-explicit] [FRICTION ROLLING_FRICTION] | settle_bench lammps-data N FILE [SEED]\n");
  return 2;
}
