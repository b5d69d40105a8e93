#include "forces/void_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/lucy_kernel.hpp"

namespace dem {

namespace {
// int_t0^t1 of sum_k h[k] t^k dt.
double poly_integral(const double* h, int n, double t0, double t1) {
  double sum = 0, p0 = t0, p1 = t1;
  for (int k = 0; k < n; ++k) {
    sum += h[k] * (p1 - p0) / (k + 1);
    p0 *= t0, p1 *= t1;
  }
  return sum;
}
}  // namespace

double ball_weight(double s, double a, double c) {
  const LucyKernel kernel(c / std::sqrt(12.0));  // support c
  const double amp = kernel.amplitude(), c2 = c * c;
  // phi(t) / amp = 1 - 6 t^2/c^2 + 8 t^3/c^3 - 3 t^4/c^4 for t < c.
  const double f[5] = {1, 0, -6 / c2, 8 / (c2 * c), -3 / (c2 * c2)};
  double w = 0;
  // The part of the support's spheres (about the origin) wholly inside the ball: t < a - s.
  const double inner = std::min(a - s, c);
  if (inner > 0) {
    double h[7] = {0, 0, f[0], f[1], f[2], f[3], f[4]};  // t^2 f(t)
    w += 4 * std::numbers::pi * poly_integral(h, 7, 0, inner);
  }
  // Spheres cut by the ball's surface: |s - a| < t < s + a, area pi t (a^2 - (s - t)^2) / s.
  const double t0 = std::abs(s - a), t1 = std::min(s + a, c);
  if (s > 0 && t1 > t0) {
    const double g[4] = {0, a * a - s * s, 2 * s, -1};  // t (a^2 - (s - t)^2)
    double h[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    for (int m = 0; m < 5; ++m)
      for (int n = 1; n < 4; ++n) h[m + n] += f[m] * g[n];
    w += std::numbers::pi / s * poly_integral(h, 8, t0, t1);
  }
  return amp * w;
}

void void_fractions(const Particles& p, const PeriodicBox& box, double c, VoidFractionScratch& sc, std::vector<double>& eps) {
  const long n = static_cast<long>(p.size());
  // Every pair whose grains the other's kernel reaches: |x_i - x_j| < c + a_j (margin c covers it).
  sc.cells.find_near_pairs(p, box, sc.pairs, sc.groups, c, true);  // held grains fill space too
  const long m = static_cast<long>(sc.pairs.size());
  sc.weight.resize(2 * m);  // 2k: grain j seen from i; 2k + 1: grain i seen from j
#pragma omp parallel for schedule(static) if (m > 2048)
  for (long k = 0; k < m; ++k) {
    const int i = sc.pairs[k].slot_i, j = sc.pairs[k].slot_j;
    const double s = box.nearest(p.x[j] - p.x[i]).norm();
    sc.weight[2 * k] = ball_weight(s, p.radius[j], c);
    sc.weight[2 * k + 1] = ball_weight(s, p.radius[i], c);
  }
  // Each particle's entries, then summed in the order of the other grain's id.
  sc.start.assign(n + 1, 0);
  for (const FoundContact& f : sc.pairs) ++sc.start[f.slot_i + 1], ++sc.start[f.slot_j + 1];
  for (long i = 0; i < n; ++i) sc.start[i + 1] += sc.start[i];
  sc.fill.assign(sc.start.begin(), sc.start.end() - 1);
  sc.entry.resize(2 * m);
  for (long k = 0; k < m; ++k) {
    sc.entry[sc.fill[sc.pairs[k].slot_i]++] = static_cast<int>(2 * k);
    sc.entry[sc.fill[sc.pairs[k].slot_j]++] = static_cast<int>(2 * k + 1);
  }
  eps.resize(n);
#pragma omp parallel for schedule(static) if (n > 128)
  for (long i = 0; i < n; ++i) {
    auto other = [&](int e) { const FoundContact& f = sc.pairs[e / 2]; return e % 2 == 0 ? f.key_j : f.key_i; };
    std::sort(sc.entry.begin() + sc.start[i], sc.entry.begin() + sc.start[i + 1], [&](int x, int y) { return other(x) < other(y); });
    double solid = ball_weight(0, p.radius[i], c);
    for (int q = sc.start[i]; q < sc.start[i + 1]; ++q) solid += sc.weight[sc.entry[q]];
    eps[i] = 1 - solid;
  }
}

}  // namespace dem
