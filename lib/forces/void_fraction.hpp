#pragma once
// The local void fraction around each particle (docs/physics.md eq. P70): one minus the grains'
// volume weighted by Lucy's kernel (core/lucy_kernel.hpp) centred on the particle,
//   eps_i = 1 - sum_j  integral over grain j of phi(y - x_i) dy ,
// each grain's integral exact (ball_weight), the sum over every grain the kernel's support
// reaches (the particle's own included), in the order of the grains' ids.
#include <vector>

#include "search/linked_cells.hpp"
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
  double weight(double s, double a) const;  // ball_weight(s, a, c)

 private:
  double c_, amp_, f2_, f3_, f4_;  // phi(t) = amp (1 + f2 t^2 + f3 t^3 + f4 t^4), t < c
};

// Working storage of void_fractions, kept between calls (no allocation once sized).
struct VoidFractionScratch {
  LinkedCells cells;
  std::vector<FoundContact> pairs;
  std::vector<int> groups;
  std::vector<double> weight;  // per pair
  std::vector<int> start, fill, entry;  // per particle: its pairs (CSR)
  std::vector<int> by_id;               // the slots in id order
  std::vector<double> ordered;          // per particle: its weights in the order of the other grain's id (CSR)
};

// eps_i for every particle (storage order), kernel support radius c [m]; pairs through the nearest
// image where `box` is periodic. The same bits for any storage order and thread count.
void void_fractions(const Particles& p, const PeriodicBox& box, double c, VoidFractionScratch& scratch, std::vector<double>& eps);

}  // namespace dem
