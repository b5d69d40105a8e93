#pragma once
// Particles as structure-of-arrays: one contiguous array per property, a stable id apart from the
// storage slot (SPEC §2: rigid spheres with 6 degrees of freedom).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

#include "core/keep_items.hpp"
#include "core/types.hpp"

namespace dem {

inline double sphere_volume(double a) { return 4.0 / 3.0 * std::numbers::pi * a * a * a; }
inline double sphere_mass(double density, double a) { return density * sphere_volume(a); }  // m = rho 4/3 pi a^3
// I = 2/5 m a^2, over a lane type as well (the four-wide motion, integrate/motion.cpp).
template <class L>
[[gnu::always_inline]] inline L sphere_inertia(const L& m, const L& a) {
  return L(0.4) * m * a * a;
}
// Values of Particles::fixed. A held or prescribed particle ignores its load (the integrator sets
// its motion) and acts on others as if infinitely heavy.
inline constexpr std::uint8_t kFree = 0;
inline constexpr std::uint8_t kHeld = 1;        // stage action `fix`: at rest
inline constexpr std::uint8_t kPrescribed = 2;  // [[stage.prescribe]]: moves at its v and w, kept constant
// Two held particles never interact (the search skips such pairs; the neighbour list is rebuilt
// when a fixed flag changes). Prescribed particles interact with all others, so that a bond
// between two of them (pulled apart at a set speed) is loaded.
// (Tested in this order so that a free particle, the common case, costs one test as before.)
inline bool both_fixed(std::uint8_t fixed_i, std::uint8_t fixed_j) { return fixed_i && fixed_j && (fixed_i & fixed_j & kHeld); }

struct Particles {
  std::vector<Index> id;
  std::vector<Vec3> x;      // position at step n [m]
  std::vector<Vec3> v;      // velocity at step n-1/2 [m/s] (central differences, eq. 2.38)
  std::vector<Vec3> w;      // angular velocity at step n-1/2 [rad/s]
  std::vector<Vec3> x_ref;  // reference position for displacement fields [m] (unwrapped)
  std::vector<Vec3i> image; // periods crossed along each axis (periodic boundaries, state/periodic.hpp)
  std::vector<double> radius;  // [m]
  std::vector<double> mass;    // [kg], m = rho 4/3 pi a^3
  std::vector<int> material;   // index into the material table
  // kHeld (1): fixed in place (as LAMMPS's fix freeze: a rough base of spheres, a fixed boundary
  // layer): never moves, and acts on others as if infinitely heavy; two held particles do not
  // interact. kPrescribed (2): moves at its own v and w for the stage ([[stage.prescribe]]), also
  // infinitely heavy in its contacts. kFree (0): moves under its load.
  std::vector<std::uint8_t> fixed;
  // The local void fraction around each particle (forces/void_fraction.hpp), while a stage has a
  // fluid; empty otherwise, and refilled whole when its size differs from the particles' (add()
  // leaves it alone).
  std::vector<double> void_fraction;

  std::size_t size() const { return id.size(); }

  void add(Index pid, const Vec3& pos, double a, double density, int mat) {
    id.push_back(pid);
    x.push_back(pos);
    v.push_back(Vec3::Zero());
    w.push_back(Vec3::Zero());
    x_ref.push_back(pos);
    image.push_back(Vec3i::Zero());
    radius.push_back(a);
    mass.push_back(sphere_mass(density, a));
    material.push_back(mat);
    fixed.push_back(0);
  }

  bool both_fixed(std::size_t i, std::size_t j) const { return dem::both_fixed(fixed[i], fixed[j]); }
  // Whether any particle is held or prescribed, and whether any is prescribed (read every step:
  // memchr scans 10^5 flags in a few microseconds, and stops at the first held particle).
  bool any_fixed() const {
    return !fixed.empty() && (std::memchr(fixed.data(), kHeld, fixed.size()) != nullptr || any_prescribed());
  }
  bool any_prescribed() const { return !fixed.empty() && std::memchr(fixed.data(), kPrescribed, fixed.size()) != nullptr; }

  double inertia(std::size_t k) const { return sphere_inertia(mass[k], radius[k]); }

  // Keep the particles for which keep[k] is true, preserving storage order.
  void keep_only(const Kept& keep);
  // Storage slot k takes the particle of slot order[k] (order: a permutation of the slots).
  void reorder(const std::vector<std::size_t>& order);
  // The storage slots in the order of the particles' ids: files list particles so, so that no
  // storage order shows in an output (it changes no result either).
  std::vector<std::size_t> slots_by_id() const;

  Index max_id() const;
};

}  // namespace dem
