#pragma once
// A test configuration with a stress known by hand: a simple cubic lattice of n^3 spheres
// (spacing s, radius a, slot (k n + j) n + i at (i, j, k) s) with the same force on every contact:
// x-contacts carry (-Fx, tau, 0) on their lower-x particle, y-contacts (0, -Fy, 0), z-contacts
// (0, 0, -Fz). Its stress is force per cell face: sigma_xx = -Fx/s^2, sigma_yy = -Fy/s^2,
// sigma_zz = -Fz/s^2, sigma_yx = tau/s^2 (force index first), sigma_xy = 0.
#include "post/contact_forces.hpp"
#include "state/particles.hpp"

namespace dem::test {

struct LoadedLattice {
  Particles p;
  ContactForceSet c;
};

inline LoadedLattice loaded_lattice(int n, double s, double a, double Fx, double Fy, double Fz, double tau) {
  LoadedLattice l;
  auto slot = [&](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) l.p.add(slot(i, j, k), Vec3(i, j, k) * s, a, 2500, 0);
  auto contact = [&](int i, int j, const Vec3& f, const Vec3& nrm) {
    l.c.pair_i.push_back(i), l.c.pair_j.push_back(j), l.c.pair_force.push_back(f), l.c.pair_normal.push_back(nrm),
        l.c.pair_bonded.push_back(0);
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) contact(slot(i, j, k), slot(i + 1, j, k), Vec3(-Fx, tau, 0), Vec3::UnitX());
        if (j + 1 < n) contact(slot(i, j, k), slot(i, j + 1, k), Vec3(0, -Fy, 0), Vec3::UnitY());
        if (k + 1 < n) contact(slot(i, j, k), slot(i, j, k + 1), Vec3(0, 0, -Fz), Vec3::UnitZ());
      }
  return l;
}

}  // namespace dem::test
