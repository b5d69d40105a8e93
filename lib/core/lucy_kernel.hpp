#pragma once
// Lucy's polynomial (Lucy 1977; used for coarse-graining by Weinhart
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
  // segment s l, s in [0, 1] (d = r - x_i for the branch vector l from x_i). For many points along
  // one segment, LucySegment below is faster.
  double segment_integral(const Vec3& d, const Vec3& l) const;

 private:
  friend class LucySegment;
  double w_, c_, c2_, amp_;
};

// The kernel integrated along one segment s l, s in [0, 1], seen from many field points.
class LucySegment {
 public:
  LucySegment(const LucyKernel& k, const Vec3& l)
      : k_(k), l_(l), L2_(l.squaredNorm()), L_(std::sqrt(L2_)), inv_L2_(L2_ > 0 ? 1 / L2_ : 0) {}

  // int_0^1 phi(d - s l) ds, d the field point's offset from the segment's start.
  double integral(const Vec3& d) const {
    if (L2_ == 0) return k_.value(d);
    const double c = k_.c_, c2 = k_.c2_;
    const double s0 = d.dot(l_) * inv_L2_;                          // foot of the perpendicular
    const double h2 = std::max(0.0, d.squaredNorm() - s0 * s0 * L2_);  // its squared distance from the line
    if (h2 >= c2) return 0.0;
    // With u = L (s - s0): r^2 = u^2 + h2, ds = du / L; the support is |u| < sqrt(c^2 - h2).
    const double half = std::sqrt(c2 - h2);
    const double u0 = -L_ * s0, u1 = L_ * (1 - s0);
    const double ua = std::max(u0, -half), ub = std::min(u1, half);
    if (ub <= ua) return 0.0;
    const double ra = ua == -half ? c : std::sqrt(ua * ua + h2);  // r = c where the support cuts
    const double rb = ub == half ? c : std::sqrt(ub * ub + h2);
    // Differences of the antiderivatives of 1, r^2, r^3 and r^4 between ua and ub.
    const double ua2 = ua * ua, ub2 = ub * ub, ua3 = ua2 * ua, ub3 = ub2 * ub;
    const double d1 = ub - ua, d3 = ub3 - ua3, d5 = ub3 * ub2 - ua3 * ua2;
    const double p2 = d3 / 3 + h2 * d1;
    const double p4 = d5 / 5 + 2 * h2 * d3 / 3 + h2 * h2 * d1;
    double p3 = (ub * (2 * ub2 + 5 * h2) * rb - ua * (2 * ua2 + 5 * h2) * ra) / 8;
    if (h2 > 0) {
      // 3 h^4 / 8 (asinh(ub/h) - asinh(ua/h)) = 3 h^4 / 8 ln((ub + rb) / (ua + ra)), with
      // u + r = h^2 / (r - u) for u < 0 (no cancellation).
      const double ga = ua >= 0 ? ua + ra : h2 / (ra - ua), gb = ub >= 0 ? ub + rb : h2 / (rb - ub);
      p3 += 3 * h2 * h2 / 8 * std::log(gb / ga);
    }
    return k_.amp_ / L_ * (d1 - 6 * p2 / c2 + 8 * p3 / (c2 * c) - 3 * p4 / (c2 * c2));
  }

 private:
  const LucyKernel& k_;
  Vec3 l_;
  double L2_, L_, inv_L2_;
};

inline double LucyKernel::segment_integral(const Vec3& d, const Vec3& l) const { return LucySegment(*this, l).integral(d); }

}  // namespace dem
