#pragma once
// The "chute" benchmark scene: the physics of LAMMPS's classic chute-flow benchmark (bench/in.chute
// upstream: 32,000 spheres, pair gran/hooke/history, gravity tilted 26 degrees, periodic in x and
// y, a rough base of frozen spheres), in its dimensionless (LJ) units: diameter 1, density 1,
// kn = 2e5, kt = 2/7 kn, gamma_n = 50 (x m_eff), no tangential damping, friction 0.5, dt = 1e-4,
// skin 0.1. Its initial state (a data file LAMMPS ships) is not ours to copy, so the state is
// regenerated here: a periodic 40 x 20 base of 800 frozen spheres at heights jittered by +-0.1
// (rough), and 31,200 free spheres above it on a touching simple cubic lattice (39 layers) with
// random velocities of up to 0.5 per component, which collapses into a dense flowing pile. The same
// state goes to LAMMPS and LIGGGHTS as a data file (bench/peers/in.chute.*). For the scaling
// benchmark the footprint grows (nx x ny columns of 40 spheres each, same depth): the same flow on
// a wider chute.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "settle_scene.hpp"  // restitution_of, write_lammps_velocities
#include "sim/simulation.hpp"

namespace dem::bench {

constexpr double kChuteKn = 2e5, kChuteGammaN = 50, kChuteAngle = 26;
constexpr int kChuteNx = 40, kChuteNy = 20, kChuteLayers = 39;

// LAMMPS's damping c = gamma_n m_eff is our c = 2 gamma sqrt(kn m_eff) with a damping ratio
// gamma = gamma_n sqrt(m_eff / kn) / 2: one restitution for free pairs (m_eff = m / 2), another
// for a free sphere on a frozen one (m_eff = m). Tangential damping off: restitution_t = 1.
inline MaterialTable chute_materials() {
  const double m = std::numbers::pi / 6;  // diameter 1, density 1
  Material free;
  free.name = "bead";
  free.density = 1;
  free.kn = kChuteKn;
  free.kt = 2.0 / 7.0 * kChuteKn;
  free.friction_angle = std::atan(0.5) * 180 / std::numbers::pi;
  free.restitution = restitution_of(kChuteGammaN * std::sqrt(m / 2 / kChuteKn) / 2);
  free.restitution_t = 1;
  Material base = free;
  base.name = "base";
  PairOverride on_base;
  on_base.a = 0;
  on_base.b = 1;
  on_base.set("restitution", restitution_of(kChuteGammaN * std::sqrt(m / kChuteKn) / 2));
  on_base.set("tangential_restitution", 1);
  return MaterialTable({free, base}, {}, {on_base});
}

// Hertz variants (hertz_models.hpp): E = 2e7, nu = 0.3 (E* = 1.1e7), restitution 0.9 (as the
// linear scene's 0.91), friction 0.5, rolling friction 0.1. The Hertz force over overlap,
// 4/3 E* sqrt(R* u), is kn = 2e5 at u = 7.5e-4 d, and the contact of a pair meeting at speed 1 lasts
// t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5) = 3.4e-3 (the linear one: 3.6e-3): dt = 1e-4 as before.
// On the frozen base the peers take m* = m (ours m/2): the ratios there are sqrt(2) larger.
constexpr HertzBead kChuteHertz{1, 2e7, 0.3, 0.9, 0.5, 0.1};

inline MaterialTable chute_hertz_materials(ContactModel model) {
  Material free = hertz_material("bead", kChuteHertz, model), base = free;
  base.name = "base";
  const Material on_base = hertz_material("on_base", kChuteHertz, model, 2);
  PairOverride pair;
  pair.a = 0;
  pair.b = 1;
  pair.set("restitution", on_base.restitution);
  pair.set("tangential_restitution", on_base.restitution_t);
  return MaterialTable({free, base}, {}, {pair});
}

inline Simulation chute_scene(int nx = kChuteNx, int ny = kChuteNy, ContactModel model = ContactModel::Linear) {
  Simulation sim;
  sim.materials = model == ContactModel::Linear ? chute_materials() : chute_hertz_materials(model);
  const double angle = kChuteAngle * std::numbers::pi / 180;
  sim.params.gravity = Vec3(std::sin(angle), 0, -std::cos(angle));  // LAMMPS: fix gravity 1.0 chute 26.0
  sim.params.skin = 0.1;
  sim.dt = 1e-4;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1), vel(-0.5, 0.5);
  Index id = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      sim.particles.add(id, Vec3(i + 0.5, j + 0.5, 0.5 + jitter(rng)), 0.5, 1, 1);
      sim.particles.fixed[id++] = 1;
    }
  for (int k = 0; k < kChuteLayers; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        sim.particles.add(id, Vec3(i + 0.5, j + 0.5, 1.7 + k), 0.5, 1, 0);
        sim.particles.v[id++] = Vec3(vel(rng), vel(rng), vel(rng));
      }
  PeriodicBox box;
  box.axis = {true, true, false};
  box.hi = Vec3(nx, ny, 0);
  sim.set_periodic(box);
  return sim;
}

// The footprint (nx, ny; twice as long as wide) whose chute holds about n spheres.
inline std::pair<int, int> chute_footprint(long n) {
  const int columns = kChuteLayers + 1;  // spheres per unit of base area
  const int nx = std::max(6, static_cast<int>(std::lround(std::sqrt(2.0 * static_cast<double>(n) / columns))));
  return {nx, std::max(3, static_cast<int>(std::lround(nx / 2.0)))};
}

// The same state as a LAMMPS/LIGGGHTS data file (atom_style sphere / granular: id type diameter
// density x y z; type 2 = the frozen base), ids from 1.
inline void write_chute_lammps_data(const Simulation& sim, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  const Particles& p = sim.particles;
  double ztop = 0;
  for (const Vec3& x : p.x) ztop = std::max(ztop, x.z() + 1);
  std::fprintf(f, "chute benchmark (dem bench/chute_scene.hpp)\n\n%zu atoms\n2 atom types\n\n", p.size());
  std::fprintf(f, "0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nAtoms\n\n", sim.periodic.hi.x(), sim.periodic.hi.y(), ztop);
  for (std::size_t k = 0; k < p.size(); ++k)
    std::fprintf(f, "%lld %d 1 1 %.17g %.17g %.17g\n", static_cast<long long>(p.id[k] + 1), p.fixed[k] ? 2 : 1, p.x[k].x(),
                 p.x[k].y(), p.x[k].z());
  write_lammps_velocities(f, p);
  std::fclose(f);
}

}  // namespace dem::bench
