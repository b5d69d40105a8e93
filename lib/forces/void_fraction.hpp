#pragma once
// The local void fraction around each particle (docs/physics.md eq. P70): one minus the grains'
// volume weighted by Lucy's kernel (core/lucy_kernel.hpp) centred on the particle,
//   eps_i = 1 - sum_j  integral over grain j of phi(y - x_i) dy ,
// each grain's integral exact (ball_weight), the sum over every grain the kernel's support
// reaches: the particle's own first, then the cells around it in a fixed order, each cell's grains
// in id order (an order set by the places and ids alone).
#include <vector>

#include "core/types.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

// The integral of Lucy's kernel of support radius c, centred at the origin, over a ball of radius
// a centred at distance s: exact (the kernel is a polynomial in the distance from its centre, and
// the area of a sphere about the origin inside the ball is pi t (a^2 - (s - t)^2) / s).
double ball_weight(double s, double a, double c);

// ball_weight for one support radius c, its constants computed once.
class LucyBall {
 public:
  explicit LucyBall(double c);
  // ball_weight(s, a, c): Pizzetti's mean value where the ball lies inside the support and away
  // from its centre (most grains), shells() elsewhere. The same to round-off.
  double weight(double s, double a) const {
    if (s > a && s + a <= c_) {
      // The kernel's polynomial f and its Laplacians there: lap f = 6 f2 + 12 f3 s + 20 f4 s^2,
      // lap^2 f = 24 f3 / s + 120 f4, lap^3 f = 0; the ball's mean f + a^2/10 lap f + a^4/280 lap^2 f.
      const double a2 = a * a;
      const double f = 1 + s * s * (f2_ + s * (f3_ + s * f4_));
      return ball_ * a2 * a * (f + a2 * (l0_ + s * (l1_ + s * l2_) + a2 * (m1_ / s + m0_)));
    }
    return shells(s, a);
  }
  // The integral over the kernel's spherical shells about its centre (any s, a).
  double shells(double s, double a) const;

 private:
  double c_, amp_, f2_, f3_, f4_;  // phi(t) = amp (1 + f2 t^2 + f3 t^3 + f4 t^4), t < c
  double ball_, l0_, l1_, l2_, m0_, m1_;  // 4 pi amp / 3; lap f / 10 = l0 + l1 s + l2 s^2; lap^2 f / 280 = m1 / s + m0
  double hc0_, hc1_, hc2_;  // shells()'s H(c) = hc0 + hc1 g1 + hc2 g2
};

// Working storage of void_fractions, kept between calls (no allocation once sized): the grains
// binned into cells of edge >= c + the largest radius, each cell's grains in id order.
struct VoidFractionScratch {
  std::vector<int> by_id;       // the slots in id order
  std::vector<int> cell_of;     // per slot, its cell
  std::vector<int> cell_first;  // per cell, where its grains start below (+ the end)
  std::vector<int> slot;        // cell by cell: the grain's slot, its place, radius, (c + radius)^2
  std::vector<Vec3> x;
  std::vector<double> radius, reach2;
  std::vector<double> x0, x1, x2;  // the places again, one array per axis (the four-wide distances)
};

// eps_i for every particle (storage order), kernel support radius c [m]; pairs through the nearest
// image where `box` is periodic (throws InputError when a period holds fewer than 3 cells of
// c + the largest radius). The same bits for any storage order and thread count.
void void_fractions(const Particles& p, const PeriodicBox& box, double c, VoidFractionScratch& scratch, std::vector<double>& eps);

}  // namespace dem
