// Contact-physics benchmarks (issue "Contact physics"):
//   contact_bench frac-sweep   speed against error: for each FRAC of docs/physics.md eq. P5, the restitution and
//                              contact-duration errors of a binary collision and the cost per
//                              simulated second of a 10,000-sphere settling scene
//   contact_bench variants     the price of each physics option on one packing: plain linear
//                              contact, walls, adhesion law with bonds (liu, mendes), mixed laws,
//                              hertz, mindlin, rolling resistance, the explicit dashpot
//   contact_bench law-price LAWS  one contact model on a dense packing (8,000 spheres on a
//                              periodic lattice, each pressed by six neighbours), 100 steps on one
//                              thread: LAWS is normal[+tangential[+rolling]], e.g. hertz+mindlin+cdt.
//   contact_bench law-price LAWS bonded  the same with every contact bonded first (F = C = 1e-2 N,
//                              as `variants`): what liu and mendes cost with their bonds
//                              Timing-independent under valgrind --tool=callgrind (instructions)
//   contact_bench law-price LAWS [bonded] STEPS  STEPS steps in place of 100 (for timings)
// Prints markdown tables; bench/run_contact_bench.sh writes them to bench/results/contact.md.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "settle_scene.hpp"
#include "contact/model_table.hpp"
#include "forces/force_loop.hpp"
#include "sim/simulation.hpp"

using namespace dem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Material bead(double eta) { return bench::settle_bead(eta); }

// Binary head-on collision of two 1 mm spheres at 0.2 m/s relative speed: realised restitution
// and contact duration against eta and pi/omega_d (the analytic answers).
void collision_errors(double frac, double eta, double& e_err, double& t_err) {
  Simulation sim;
  sim.materials = MaterialTable({bead(eta)}, {});
  sim.params.gravity = Vec3::Zero();
  const double a = 0.001, v0 = 0.1;
  sim.particles.add(0, Vec3(0, 0, 1.001 * a), a, 2500, 0);
  sim.particles.add(1, Vec3(0, 0, -1.001 * a), a, 2500, 0);
  sim.particles.v[0] = Vec3(0, 0, -v0);
  sim.particles.v[1] = Vec3(0, 0, v0);
  sim.dt = frac * sim.critical_time_step();
  int steps = 0;
  bool touched = false;
  for (int s = 0; s < 10000000; ++s) {
    sim.advance();
    const bool c = sim.pair_contacts().size() > 0;
    steps += c;
    touched = touched || c;
    if (touched && !c) break;
  }
  const double e = (sim.particles.v[0].z() - sim.particles.v[1].z()) / (2 * v0);
  const double m_eff = sphere_mass(2500, a) / 2;
  const double l = std::log(eta), gamma = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  const double tc = std::numbers::pi / (std::sqrt(2000 / m_eff) * std::sqrt(1 - gamma * gamma));
  e_err = (e - eta) / eta;
  t_err = (steps * sim.dt - tc) / tc;
}

// The settle scene of bench/settle_scene.hpp with one material (walls included) of restitution eta.
Simulation settle_scene(int nx, int ny, int nz, double eta, bool walls) {
  Simulation sim = bench::settle_scene({nx, ny, nz}, eta, walls);
  sim.materials = MaterialTable({bead(eta)}, {});
  for (Wall& w : sim.walls) w.material = 0;
  return sim;
}

void frac_sweep() {
  std::printf("| FRAC | steps per contact | restitution error, eta = 0.9 | eta = 0.5 | eta = 0.3 | eta = 0.05 | contact-time error, eta = 0.5 | "
              "eta = 0.05 | settle 10k: wall s per simulated s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (double frac : {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5}) {
    double e9, t9, e5, t5, e3, t3, e05, t05;
    collision_errors(frac, 0.9, e9, t9);
    collision_errors(frac, 0.5, e5, t5);
    collision_errors(frac, 0.3, e3, t3);
    collision_errors(frac, 0.05, e05, t05);
    Simulation sim = settle_scene(25, 25, 16, 0.5, true);
    sim.dt = frac * sim.critical_time_step();
    for (int k = 0; k < 200; ++k) sim.advance();  // warm up: contacts form
    const int steps = 2000;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) sim.advance();
    const double wall = seconds_since(t0);
    const double m = sphere_mass(2500, 0.001) / 2;
    std::printf("| %.2f | %.0f | %+.2f %% | %+.2f %% | %+.2f %% | %+.2f %% | %+.2f %% | %+.2f %% | %.3g |\n", frac,
                std::numbers::pi * std::sqrt(m / 2000) / sim.dt, 100 * e9, 100 * e5, 100 * e3, 100 * e05, 100 * t5, 100 * t05,
                wall / (steps * sim.dt));
    std::fflush(stdout);
  }
}

void variants() {
  // One packing for all variants: the settle scene after 0.1 s, when it has collapsed into a pile.
  // Each variant then runs 300 steps from that same state, so all see the same contacts.
  Simulation base = settle_scene(25, 25, 16, 0.5, true);
  base.dt = 0.1 * base.critical_time_step();
  while (base.time < 0.1) base.advance();
  std::printf("| variant | force loop | contacts | ns per particle-step, 1 thread | ns per particle-step, 2 threads | relative to cundall + walls (1 thread) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  double reference = 0;
  struct Case {
    const char* name;
    NormalLaw law;
    bool extra_walls, bonds;
    TangentialLaw tangential = TangentialLaw::Coulomb;
    RollingLaw rolling = RollingLaw::None;
    bool explicit_dashpot = false;  // docs/contact-laws.md eq. D7
  };
  const Case cases[] = {{"cundall, 6 walls", NormalLaw::Cundall, false, false},
                        {"cundall, 6 more walls far away (no contacts)", NormalLaw::Cundall, true, false},
                        {"liu law, no bond formed", NormalLaw::Liu, false, false},
                        {"liu, every contact bonded", NormalLaw::Liu, false, true},
                        {"mendes, every contact bonded", NormalLaw::Mendes, false, true},
                        {"cundall + cdt rolling resistance", NormalLaw::Cundall, false, false, TangentialLaw::Coulomb, RollingLaw::ConstantTorque},
                        {"cundall + epsd2 rolling resistance", NormalLaw::Cundall, false, false, TangentialLaw::Coulomb, RollingLaw::ElasticPlastic},
                        {"hertz, linear tangential spring", NormalLaw::Hertz, false, false},
                        {"hertz + mindlin", NormalLaw::Hertz, false, false, TangentialLaw::Mindlin},
                        {"hertz + mindlin + cdt", NormalLaw::Hertz, false, false, TangentialLaw::Mindlin, RollingLaw::ConstantTorque},
                        {"hertz + mindlin + epsd2", NormalLaw::Hertz, false, false, TangentialLaw::Mindlin, RollingLaw::ElasticPlastic},
                        {"cundall, explicit dashpot", NormalLaw::Cundall, false, false, TangentialLaw::Coulomb, RollingLaw::None, true},
                        {"hertz + mindlin, explicit dashpot", NormalLaw::Hertz, false, false, TangentialLaw::Mindlin, RollingLaw::None, true}};
  for (const Case& c : cases) {
    double ns[2];
    std::size_t contacts = 0;
    std::string variant;
    for (int t = 0; t < 2; ++t) {
      Simulation sim = base;
      Material m = bead(0.5);
      m.law = c.law;
      m.tensile_strength = 1e-2;  // N: strong enough that bonds hold over the run
      m.cohesion = 1e-2;
      m.tangential = c.tangential;
      m.rolling = c.rolling;
      m.rolling_friction = 0.1;
      m.explicit_dashpot = c.explicit_dashpot;
      // Hertz as stiff as kn = 2000 N/m where a bead carries its weight (u ~ 5e-8 m).
      m.young_modulus = 5e8;
      m.poisson_ratio = 0.3;
      sim.materials = MaterialTable({m}, {});
      // Removing the walls would let the loaded pile spring apart; instead, the cost of walls is
      // shown by adding six that touch nothing (each particle is still tested against each wall).
      if (c.extra_walls)
        for (int k = 0; k < 6; ++k) {
          Wall w = sim.walls[k];
          for (Vec3& v : w.base) v += Vec3(1, 1, 1);
          sim.walls.push_back(w);
        }
      if (c.bonds) sim.bond_present_contacts(true);
      variant = variant_name(choose_force_variant(sim.materials, sim.has_bonds()));
      omp_set_num_threads(t == 0 ? 1 : 2);
      const int steps = 300;
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = 0; k < steps; ++k) sim.advance();
      ns[t] = 1e9 * seconds_since(t0) / (steps * sim.particles.size());
      contacts = sim.pair_contacts().size() + sim.wall_contacts().size();
    }
    if (reference == 0) reference = ns[0];
    std::printf("| %s | %s | %zu | %.0f | %.0f | %.2f |\n", c.name, variant.c_str(), contacts, ns[0], ns[1], ns[0] / reference);
    std::fflush(stdout);
  }
}

// `hertz+mindlin+epsd2` -> its laws; throws on an unknown name.
ModelChoice parse_laws(const std::string& text) {
  ModelChoice m;
  std::string rest = text;
  auto next = [&] {
    const std::size_t plus = rest.find('+');
    std::string part = rest.substr(0, plus);
    rest = plus == std::string::npos ? "" : rest.substr(plus + 1);
    return part;
  };
  const auto need = [&](auto found, const std::string& what) {
    if (!found) throw std::invalid_argument("unknown law \"" + what + "\"");
    return *found;
  };
  std::string part = next();
  m.normal = need(normal_law_named(part), part);
  if (!rest.empty()) part = next(), m.tangential = need(tangential_law_named(part), part);
  if (!rest.empty()) part = next(), m.rolling = need(rolling_law_named(part), part);
  return m;
}

void law_price(const std::string& laws, bool bonded, int steps) {
  const ModelChoice models = parse_laws(laws);
  Material m = bead(0.5);
  m.law = models.normal, m.tangential = models.tangential, m.rolling = models.rolling;
  m.young_modulus = 5e8, m.poisson_ratio = 0.3, m.rolling_friction = 0.1;
  m.tensile_strength = m.cohesion = 1e-2;  // N: as variants(); read only by bonded contacts
  Simulation sim;
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3::Zero();
  constexpr int kSide = 20;
  constexpr double kRadius = 1e-3, kSpacing = 0.999 * 2 * kRadius;  // every sphere pressed by six
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  Index id = 0;
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        sim.particles.add(id, kSpacing * Vec3(i + 0.5, j + 0.5, k + 0.5), kRadius, m.density, 0);
        sim.particles.w[id] = Vec3(u(rng), u(rng), u(rng)) / kRadius;  // the rolling laws have work
        sim.particles.v[id++] = Vec3(u(rng), u(rng), u(rng));
      }
  PeriodicBox box;
  box.axis = {true, true, true};
  box.hi = Vec3::Constant(kSpacing * kSide);
  sim.set_periodic(box);
  sim.dt = 0.1 * sim.critical_time_step();
  if (bonded) sim.bond_present_contacts(false);
  omp_set_num_threads(1);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) sim.advance();
  std::printf("%s%s: force loop %s, %zu pair contacts, %.0f ns per particle-step (1 thread)\n", laws.c_str(), bonded ? " bonded" : "",
              variant_name(choose_force_variant(sim.materials, sim.has_bonds())).c_str(), active_count(sim.pair_contacts()),
              1e9 * seconds_since(t0) / (steps * sim.particles.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && std::strcmp(argv[1], "law-price") == 0) {
    int next = 3;
    const bool bonded = next < argc && std::strcmp(argv[next], "bonded") == 0;
    next += bonded;
    char* end = nullptr;
    const long steps = next < argc ? std::strtol(argv[next], &end, 10) : 100;
    if (next + 1 < argc || (next < argc && (*end != '\0' || steps < 1 || steps > 1000000))) {
      std::fprintf(stderr, "contact_bench law-price LAWS [bonded] [STEPS]: STEPS '%s' must be a whole number from 1 to 1000000\n",
                   argv[argc - 1]);
      return 2;
    }
    law_price(argv[2], bonded, static_cast<int>(steps));
    return 0;
  }
  if (argc == 2 && std::strcmp(argv[1], "frac-sweep") == 0) frac_sweep();
  else if (argc == 2 && std::strcmp(argv[1], "variants") == 0) variants();
  else {
    std::fprintf(stderr, "usage: contact_bench frac-sweep|variants|law-price LAWS [bonded] [STEPS]\n");
    return 2;
  }
  return 0;
}
