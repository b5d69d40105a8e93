#pragma once
// The coarse-graining kernel: an isotropic Gaussian of standard deviation w (the "width"),
// truncated at r = 3w and renormalised so that it integrates to exactly 1 over space:
//   phi(r) = A exp(-r^2 / (2 w^2)) for r < 3w, 0 beyond,  A = 1 / ((2 pi)^{3/2} w^3 P),
// with P = erf(3/sqrt 2) - sqrt(2/pi) 3 e^{-9/2} = 0.97070..., the share of an untruncated 3-D
// Gaussian inside radius 3w. Besides point values, the contact stress needs the kernel's integral
// along a segment (Goldhirsch 2010, Weinhart et al. 2012), which is exact here: along a line the
// truncation is an interval of the line parameter, and the Gaussian integrates to erf.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/types.hpp"

namespace dem {

class GaussianKernel {
 public:
  explicit GaussianKernel(double width)
      : w_(width), cut_(3 * width), inv2w2_(1 / (2 * width * width)) {
    const double c = 3;  // cut-off in units of w
    const double share = std::erf(c / std::numbers::sqrt2) - std::sqrt(2 / std::numbers::pi) * c * std::exp(-c * c / 2);
    amp_ = 1 / (std::pow(2 * std::numbers::pi, 1.5) * width * width * width * share);
  }

  double width() const { return w_; }
  double cutoff() const { return cut_; }  // 3 w: phi is zero at and beyond
  double amplitude() const { return amp_; }
  // exp(-t^2 / (2 w^2)): the per-axis factor of phi (phi = A ex ey ez inside the cut-off sphere).
  double axis_factor(double t) const { return std::exp(-t * t * inv2w2_); }

  double value(const Vec3& r) const {
    const double r2 = r.squaredNorm();
    return r2 < cut_ * cut_ ? amp_ * std::exp(-r2 * inv2w2_) : 0.0;
  }

  // int_0^1 phi(d - s l) ds: the kernel seen by a field point at offset d from the start of the
  // segment s l, s in [0, 1] (d = r - x_i for the branch vector l from x_i).
  double segment_integral(const Vec3& d, const Vec3& l) const {
    const double L2 = l.squaredNorm();
    if (L2 == 0) return value(d);
    const double s0 = d.dot(l) / L2;                              // foot of the perpendicular from the point
    const double h2 = std::max(0.0, d.squaredNorm() - s0 * s0 * L2);  // its squared distance from the line
    const double c2 = cut_ * cut_;
    if (h2 >= c2) return 0.0;
    const double L = std::sqrt(L2);
    const double half = std::sqrt(c2 - h2) / L;  // |s - s0| < half inside the cut-off sphere
    const double sa = std::max(0.0, s0 - half), sb = std::min(1.0, s0 + half);
    if (sb <= sa) return 0.0;
    // A e^{-h^2/2w^2} int_sa^sb e^{-L^2 (s - s0)^2 / 2w^2} ds
    const double k = L / (std::numbers::sqrt2 * w_);
    return amp_ * std::exp(-h2 * inv2w2_) * (std::sqrt(std::numbers::pi) / (2 * k)) * (std::erf(k * (sb - s0)) - std::erf(k * (sa - s0)));
  }

 private:
  double w_, cut_, inv2w2_, amp_ = 0;
};

}  // namespace dem
