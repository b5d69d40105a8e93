#pragma once
// Coarse-grained continuum fields on a regular grid (docs/physics.md eq. P27; Goldhirsch 2010, Weinhart et al.
// 2012), with Lucy's kernel phi of post/kernel.hpp (standard deviation w along each axis, support
// radius c = sqrt(12) w):
//   density         rho(r) = sum_p m_p phi(r - x_p)                                   [kg/m^3]
//   solid fraction  nu(r)  = sum_p V_p phi(r - x_p)                                   [1]
//   velocity        V(r)   = sum_p m_p v_p phi(r - x_p) / rho(r)   (0 where rho = 0)   [m/s]
//   contact stress  sigma_c(r) = sum_c f_c (x) l_c int_0^1 phi(r - x_c0 - s l_c) ds     [Pa]
//                   (pair: f on i, l = x_j - x_i from x_i; wall: f on the particle, l from its
//                   centre to the contact point; fibre segment: T e on a, l = x_b - x_a from x_a,
//                   eq. P64 spread as P27, docs/physics.md eq. P65), force index first and
//                   tension positive as in post/stress.hpp. It satisfies momentum balance
//                   exactly: away from walls, div sigma_c = - sum_p phi(r - x_p) F_p (F_p the
//                   particles' contact and fibre forces).
//   kinetic stress  sigma_k(r) = -sum_p m_p (v_p - V(r))(x)(v_p - V(r)) phi(r - x_p)    [Pa]
//   displacement    U(r): the value at r of the linear field u = a + G (x - r) that best fits
//                   the particles' displacements, weighted by m_p phi(r - x_p) (least squares;
//                   exact for any affine displacement); G = du/dx in the current configuration.
//   gradient        du/dX = (I - G)^{-1} - I (since X = x - u), i.e. F - I;
//                   strain eps = (du/dX + du/dX^T)/2 (infinitesimal, tension positive).
// Displacement and its gradient are NaN where the fit is undefined: the weighted particles
// span less than 0.1 w in some direction (fewer than four in reach, or all nearly in a plane).
#include <array>
#include <cstddef>
#include <vector>

#include "core/types.hpp"
#include "post/contact_forces.hpp"
#include "post/stress.hpp"
#include "state/particles.hpp"

namespace dem {

// Nodes origin + (i, j, k) cell, 0 <= i < n[0] etc.; node (i, j, k) is entry i + n0 (j + n1 k)
// (x fastest, as VTK image data).
struct GridSpec {
  Vec3 origin = Vec3::Zero();
  double cell = 0;
  std::array<long, 3> n{0, 0, 0};
  std::size_t nodes() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  Vec3 node(long i, long j, long k) const { return origin + cell * Vec3(i, j, k); }
};

// The grid with nodes from box.lo in steps of `cell`, reaching box.hi or just beyond:
// n = ceil((hi - lo) / cell) + 1 per axis (a flat box gives one layer of nodes).
GridSpec grid_covering(const Box& box, double cell);

struct GridFields {
  GridSpec grid;
  double width = 0;
  std::vector<double> density, solid_fraction;
  std::vector<Vec3> velocity;
  std::vector<Mat3> contact_stress, kinetic_stress;
  // Only with a displacement per particle:
  std::vector<Vec3> displacement;
  std::vector<Mat3> displacement_gradient;  // du/dX
};

// `u`: displacement per particle (NaN where not matched: left out of the fit), or null.
// Plane by plane of nodes, each plane by one thread adding its particles and contacts in a fixed
// order: the same bits for any thread count.
// `fibres`: the fibres' segments (post/stress.hpp fibre_branches), or null: none.
GridFields coarse_grain(const Particles& p, const ContactForceSet& c, const std::vector<Vec3>* u, const GridSpec& grid, double width,
                        const FibreBranches* fibres = nullptr);

}  // namespace dem
