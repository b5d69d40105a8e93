// The chute benchmark for our code (bench/run_peer_bench.sh runs it beside LAMMPS and LIGGGHTS):
//   chute_bench run STEPS THREADS [MODEL]
//                                    runs the scene of bench/chute_scene.hpp for STEPS steps and
//                                    prints one line (bench_report.hpp): loop seconds,
//                                    particle-steps per second, contacts, energies, peak memory;
//                                    MODEL linear (default), hertz, hertz-rolling, hertz-explicit or hertz-rolling-explicit
//   chute_bench scaled N STEPS THREADS
//                                    the same flow on a wider chute of about N spheres (same depth,
//                                    chute_footprint): the cost per particle-step against N
//   chute_bench lattice N STEPS THREADS
//                                    about N spheres pressed together on a periodic lattice
//                                    (lattice_scene.hpp): 6 contacts per sphere at any N, the
//                                    code's own cost per particle-step against N
//   chute_bench lammps-data FILE     writes the same initial state as a LAMMPS data file
// The loop time covers the steps only (scene construction excluded), as LAMMPS's "Loop time".
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "bench_report.hpp"
#include "chute_scene.hpp"
#include "lattice_scene.hpp"

using namespace dem;

int main(int argc, char** argv) {
  try {
    const bool run = (argc == 4 || argc == 5) && std::strcmp(argv[1], "run") == 0;
    const bool scaled = argc == 5 && std::strcmp(argv[1], "scaled") == 0;
    const bool lattice = argc == 5 && std::strcmp(argv[1], "lattice") == 0;
    if (run || scaled || lattice) {
      const int last = run ? 3 : 4;  // THREADS
      const long steps = std::atol(argv[last - 1]);
      const int threads = std::atoi(argv[last]);
      const bench::ContactModel model = bench::contact_model_named(run && argc == 5 ? argv[4] : "linear");
      omp_set_num_threads(threads);
      const long rss_before = bench::peak_rss_kb();
      const auto [nx, ny] = scaled ? bench::chute_footprint(std::atol(argv[2])) : std::pair{bench::kChuteNx, bench::kChuteNy};
      Simulation sim = lattice ? bench::lattice_scene(std::atol(argv[2])) : bench::chute_scene(nx, ny, model);
      bench::timed_run(sim, steps, threads, rss_before);
      return 0;
    }
    if (argc == 3 && std::strcmp(argv[1], "lammps-data") == 0) {
      bench::write_chute_lammps_data(bench::chute_scene(), argv[2]);
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chute_bench: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: chute_bench run STEPS THREADS [linear|hertz|hertz-rolling|hertz-explicit|hertz-rolling-explicit] | chute_bench scaled N STEPS THREADS | chute_bench lattice N STEPS THREADS | "
                       "chute_bench lammps-data FILE\n");
  return 2;
}
