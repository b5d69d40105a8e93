#pragma once
// The coarse-graining kernel: Lucy's polynomial (Lucy 1977; used for coarse-graining by Weinhart
// et al. 2012, 2016), with compact support of radius c:
//   phi(r) = A (1 + 3q)(1 - q)^3 = A (1 - 6q^2 + 8q^3 - 3q^4),  q = r/c < 1,  A = 105 / (16 pi c^3),
// zero for r >= c. It integrates to exactly 1 over space and is smooth everywhere: value, slope
// and curvature all vanish at r = c, so unlike a Gaussian cut at 3w it adds no ripple at the
// cut-off (a Gaussian cut at 3w ripples by ~1 % of the density on a regular lattice).
// The user's `width` w is the kernel's standard deviation along any axis, as for a Gaussian of
// width w: <x^2> = c^2/12, so c = sqrt(12) w = 3.46 w.
// Besides point values, the contact stress needs the kernel's integral along a segment
// (Goldhirsch 2010, Weinhart et al. 2012), which is exact here: along a line r^2 is quadratic in
// the line parameter, and every power of r integrates in closed form.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/types.hpp"

namespace dem {

class LucyKernel {
 public:
  explicit LucyKernel(double width)
      : w_(width), c_(std::sqrt(12.0) * width), c2_(c_ * c_), amp_(105 / (16 * std::numbers::pi * c_ * c_ * c_)) {}

  double width() const { return w_; }
  double cutoff() const { return c_; }  // phi is zero at and beyond
  double amplitude() const { return amp_; }

  // phi at squared distance r2.
  double value_r2(double r2) const {
    if (r2 >= c2_) return 0.0;
    const double q = std::sqrt(r2) / c_;
    return amp_ * (1 + 3 * q) * (1 - q) * (1 - q) * (1 - q);
  }
  double value(const Vec3& r) const { return value_r2(r.squaredNorm()); }

  // int_0^1 phi(d - s l) ds: the kernel seen by a field point at offset d from the start of the
  // segment s l, s in [0, 1] (d = r - x_i for the branch vector l from x_i).
  double segment_integral(const Vec3& d, const Vec3& l) const {
    const double L2 = l.squaredNorm();
    if (L2 == 0) return value(d);
    const double s0 = d.dot(l) / L2;                                   // foot of the perpendicular
    const double h2 = std::max(0.0, d.squaredNorm() - s0 * s0 * L2);  // its squared distance from the line
    if (h2 >= c2_) return 0.0;
    const double L = std::sqrt(L2);
    const double half = std::sqrt(c2_ - h2) / L;  // |s - s0| < half inside the support
    const double sa = std::max(0.0, s0 - half), sb = std::min(1.0, s0 + half);
    if (sb <= sa) return 0.0;
    // With u = L (s - s0): r^2 = u^2 + h^2, ds = du / L.
    return amp_ / L * (antiderivative(L * (sb - s0), h2) - antiderivative(L * (sa - s0), h2));
  }

 private:
  // int (1 - 6 r^2/c^2 + 8 r^3/c^3 - 3 r^4/c^4) du with r^2 = u^2 + h2.
  double antiderivative(double u, double h2) const {
    const double u2 = u * u, r2 = u2 + h2;
    const double p2 = u * (u2 / 3 + h2);                       // int r^2
    const double p4 = u * (u2 * u2 / 5 + 2 * h2 * u2 / 3 + h2 * h2);  // int r^4
    double p3 = u / 8 * (2 * u2 + 5 * h2) * std::sqrt(r2);     // int r^3
    if (h2 > 0) p3 += 3 * h2 * h2 / 8 * std::asinh(u / std::sqrt(h2));
    return u - 6 * p2 / c2_ + 8 * p3 / (c2_ * c_) - 3 * p4 / (c2_ * c2_);
  }

  double w_, c_, c2_, amp_;
};

}  // namespace dem
