#pragma once
// The "settle" benchmark scene, regenerated here so that the benchmarks need nothing outside the
// repository: N spheres of radius 1 mm (rho 2500) on a simple cubic lattice of spacing 2.5 mm
// (sites at (i + 1/2) s) with random velocities in [-0.1, 0.1] m/s per component, falling under
// gravity into a closed box of six planar walls (nx s, ny s, (nz + 2) s). Linear spring-dashpot with
// kn = 2000 N/m, kt = 2/7 kn, friction 0.5, dt = 1e-5 s, skin 0.2 mm: the scene with which LAMMPS
// and LIGGGHTS were run (bench/peers/in.settle.*), with our damping set to their coefficients.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "contact/damping.hpp"
#include "hertz_models.hpp"
#include "sim/simulation.hpp"

namespace dem::bench {

// Materials matching LAMMPS's gran/hooke/history with gamma_n x m_eff damping and gamma_t = gamma_n / 2:
// - particle-particle: eta = 0.5 (m_eff = m/2);
// - particle-wall: LAMMPS uses the particle-particle gamma_n with m_eff = m, i.e. a damping ratio
//   sqrt(2) larger (eta = 0.366);
// - tangential: c_t = c_n / 2. Ours is c_t = 2 gamma_t sqrt(2/7 m_eff kt) with kt = 2/7 kn (see
//   contact/contact_law.hpp), so gamma_t = 7/4 gamma_n.
// A 2500 kg/m^3 bead, kn = 2000 N/m, kt = 2/7 kn, friction 0.5, restitution eta (both).
inline Material settle_bead(double eta) {
  Material bead;
  bead.name = "bead";
  bead.density = 2500;
  bead.kn = 2000;
  bead.kt = 2.0 / 7.0 * 2000;
  bead.friction_angle = std::atan(0.5) * 180 / std::numbers::pi;
  bead.restitution = bead.restitution_t = eta;
  return bead;
}

inline MaterialTable settle_materials(double eta = 0.5) {
  Material bead = settle_bead(eta);
  const double g = damping_ratio(eta);
  bead.restitution_t = restitution_of(7.0 / 4.0 * g);
  Material wall = bead;
  wall.name = "wall";
  PairOverride bw;
  bw.a = 0;
  bw.b = 1;
  bw.set("restitution", restitution_of(std::sqrt(2.0) * g));
  bw.set("tangential_restitution", restitution_of(7.0 / 4.0 * std::sqrt(2.0) * g));
  return MaterialTable({bead, wall}, {}, {bw});
}

// Hertz variants (hertz_models.hpp): glass-like beads made soft, E = 5 MPa, nu = 0.3, restitution
// 0.5, friction 0.5, rolling friction 0.1; walls of the same material (R* = a, m* = m, as the
// peers). At the impact speeds here (<= 1 m/s) the Hertz contact lasts t_c = 2.87 (m*^2 / (R* E*^2
// v))^(1/5) >= 2.7e-4 s for a pair: dt = 5e-6 s is t_c/54.
constexpr HertzBead kSettleHertz{2500, 5e6, 0.3, 0.5, 0.5, 0.1};
constexpr double kSettleHertzDt = 5e-6;

inline MaterialTable settle_hertz_materials(ContactModel model, const HertzBead& b = kSettleHertz) {
  Material bead = hertz_material("bead", b, model), wall = bead;
  wall.name = "wall";
  return MaterialTable({bead, wall}, {});
}

struct LatticeSize {
  int nx, ny, nz;
  long count() const { return static_cast<long>(nx) * ny * nz; }
};

// The peers' sizes for 10^4 and 10^5; other sizes: a box twice as wide as high.
inline LatticeSize settle_size(long n) {
  if (n == 10000) return {25, 25, 16};
  if (n == 100000) return {50, 50, 40};
  const int nz = std::max(1, static_cast<int>(std::lround(std::cbrt(n / 4.0))));
  const int nx = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n) / nz))));
  const LatticeSize s{nx, nx, static_cast<int>(std::lround(static_cast<double>(n) / (nx * nx)))};
  if (s.count() != n) throw std::runtime_error("settle: N must be 10000, 100000 or fill a lattice nx x nx x nz exactly (e.g. 1000000)");
  return s;
}

constexpr double kSpacing = 0.0025, kRadius = 0.001, kDensity = 2500;

inline Vec3 settle_box(const LatticeSize& s) { return Vec3(s.nx * kSpacing, s.ny * kSpacing, (s.nz + 2) * kSpacing); }

// `seed` draws the initial velocities (12345: the speed benchmarks' state); `hertz` is the Hertz
// models' material (the side-by-side check, bench/peers/run_side_by_side.sh, varies it).
inline Simulation settle_scene(const LatticeSize& size, double eta = 0.5, bool walls = true, ContactModel model = ContactModel::Linear,
                               std::uint64_t seed = 12345, const HertzBead& hertz = kSettleHertz) {
  Simulation sim;
  sim.materials = model == ContactModel::Linear ? settle_materials(eta) : settle_hertz_materials(model, hertz);
  const Vec3 hi = settle_box(size);
  if (walls)
    for (int axis = 0; axis < 3; ++axis)
      for (bool side : {false, true}) sim.walls.push_back(Wall{"w", 1, box_face(Vec3::Zero(), hi, axis, side), {}});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> vel(-0.1, 0.1);
  Index id = 0;
  for (int k = 0; k < size.nz; ++k)
    for (int j = 0; j < size.ny; ++j)
      for (int i = 0; i < size.nx; ++i) {
        sim.particles.add(id, Vec3((i + 0.5) * kSpacing, (j + 0.5) * kSpacing, (k + 0.5) * kSpacing), kRadius, kDensity, 0);
        sim.particles.v[id] = Vec3(vel(rng), vel(rng), vel(rng));
        ++id;
      }
  sim.params.gravity = Vec3(0, 0, -9.81);
  sim.params.skin = 0.0002;
  sim.dt = model == ContactModel::Linear ? 1e-5 : kSettleHertzDt;
  return sim;
}

// The Velocities section of a LAMMPS data file (ids from 1, no spin).
inline void write_lammps_velocities(std::FILE* f, const Particles& p) {
  std::fprintf(f, "\nVelocities\n\n");
  for (std::size_t k = 0; k < p.size(); ++k)
    std::fprintf(f, "%lld %.17g %.17g %.17g 0 0 0\n", static_cast<long long>(p.id[k] + 1), p.v[k].x(), p.v[k].y(), p.v[k].z());
}

// The same particles as a LAMMPS/LIGGGHTS data file (atom_style sphere / granular), ids from 1.
inline void write_lammps_data(const Simulation& sim, const LatticeSize& size, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  const Vec3 hi = settle_box(size);
  const Particles& p = sim.particles;
  std::fprintf(f, "settle benchmark N=%zu (dem bench/settle_scene.hpp)\n\n%zu atoms\n1 atom types\n\n", p.size(), p.size());
  std::fprintf(f, "0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nAtoms\n\n", hi.x(), hi.y(), hi.z());
  for (std::size_t k = 0; k < p.size(); ++k)
    std::fprintf(f, "%lld 1 %.17g %.17g %.17g %.17g %.17g\n", static_cast<long long>(p.id[k] + 1), 2 * p.radius[k], kDensity, p.x[k].x(),
                 p.x[k].y(), p.x[k].z());
  write_lammps_velocities(f, p);
  std::fclose(f);
}

}  // namespace dem::bench
