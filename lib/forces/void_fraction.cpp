#include "forces/void_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/lucy_kernel.hpp"

namespace dem {

LucyBall::LucyBall(double c)
    : c_(c), amp_(LucyKernel(c / std::sqrt(12.0)).amplitude()), f2_(-6 / (c * c)), f3_(8 / (c * c * c)), f4_(-3 / (c * c * c * c)) {}

double LucyBall::weight(double s, double a) const {
  // phi(t) / amp = f(t) = 1 + f2 t^2 + f3 t^3 + f4 t^4 for t < c (Lucy's polynomial, P70).
  double w = 0;
  // The part of the support's spheres (about the origin) wholly inside the ball: t < a - s,
  // 4 pi int_0^inner t^2 f(t) dt.
  const double inner = std::min(a - s, c_);
  if (inner > 0) {
    const double t = inner;
    w += 4 * std::numbers::pi * t * t * t * (1.0 / 3 + t * t * (f2_ / 5 + t * (f3_ / 6 + t * (f4_ / 7))));
  }
  // Spheres cut by the ball's surface: |s - a| < t < s + a, area pi t (a^2 - (s - t)^2) / s, so
  // pi/s int_t0^t1 t (a^2 - (s - t)^2) f(t) dt: the polynomial h(t) = (g1 t + g2 t^2 - t^3) f(t),
  // g1 = a^2 - s^2, g2 = 2 s, integrated term by term (Horner in t; H(t) = sum h_k t^(k+1)/(k+1)).
  const double t0 = std::abs(s - a), t1 = std::min(s + a, c_);
  if (s > 0 && t1 > t0) {
    const double g1 = a * a - s * s, g2 = 2 * s;
    const double H1 = g1 / 2, H2 = g2 / 3, H3 = (-1 + f2_ * g1) / 4, H4 = (f2_ * g2 + f3_ * g1) / 5,
                 H5 = (-f2_ + f3_ * g2 + f4_ * g1) / 6, H6 = (-f3_ + f4_ * g2) / 7, H7 = -f4_ / 8;
    auto H = [&](double t) { return t * t * (H1 + t * (H2 + t * (H3 + t * (H4 + t * (H5 + t * (H6 + t * H7)))))); };
    w += std::numbers::pi / s * (H(t1) - H(t0));
  }
  return amp_ * w;
}

double ball_weight(double s, double a, double c) { return LucyBall(c).weight(s, a); }

void void_fractions(const Particles& p, const PeriodicBox& box, double c, VoidFractionScratch& sc, std::vector<double>& eps) {
  const long n = static_cast<long>(p.size());
  const LucyBall ball(c);
  // Every pair whose grains the other's kernel reaches: |x_i - x_j| < c + a_j (margin c covers it).
  sc.cells.find_near_pairs(p, box, sc.pairs, sc.groups, c, true);  // held grains fill space too
  const long m = static_cast<long>(sc.pairs.size());
  sc.weight.resize(2 * m);  // 2k: grain j seen from i; 2k + 1: grain i seen from j
#pragma omp parallel for schedule(static) if (m > 2048)
  for (long k = 0; k < m; ++k) {
    const int i = sc.pairs[k].slot_i, j = sc.pairs[k].slot_j;
    const double s = box.nearest(p.x[j] - p.x[i]).norm();
    sc.weight[2 * k] = ball.weight(s, p.radius[j]);
    sc.weight[2 * k + 1] = ball.weight(s, p.radius[i]);
  }
  // Each particle's entries (CSR: start, entry) in no particular order.
  sc.start.assign(n + 1, 0);
  for (const FoundContact& f : sc.pairs) ++sc.start[f.slot_i + 1], ++sc.start[f.slot_j + 1];
  for (long i = 0; i < n; ++i) sc.start[i + 1] += sc.start[i];
  sc.fill.assign(sc.start.begin(), sc.start.end() - 1);
  sc.entry.resize(2 * m);
  for (long k = 0; k < m; ++k) {
    sc.entry[sc.fill[sc.pairs[k].slot_i]++] = static_cast<int>(2 * k);
    sc.entry[sc.fill[sc.pairs[k].slot_j]++] = static_cast<int>(2 * k + 1);
  }
  // Then each particle's weights in the order of the other grain's id, without a sort per particle:
  // visiting the grains o in id order, o's entry e (o seen by its partner is e ^ 1) goes to the
  // partner's list, which so fills in the order of o's id.
  sc.by_id.resize(n);
  for (long i = 0; i < n; ++i) sc.by_id[i] = static_cast<int>(i);
  std::sort(sc.by_id.begin(), sc.by_id.end(), [&](int a, int b) { return p.id[a] < p.id[b]; });
  sc.fill.assign(sc.start.begin(), sc.start.end() - 1);
  sc.ordered.resize(2 * m);
  for (const int o : sc.by_id)
    for (int q = sc.start[o]; q < sc.start[o + 1]; ++q) {
      const int e = sc.entry[q];
      const FoundContact& f = sc.pairs[e / 2];
      const int partner = e % 2 == 0 ? f.slot_j : f.slot_i;
      sc.ordered[sc.fill[partner]++] = sc.weight[e ^ 1];
    }
  eps.resize(n);
#pragma omp parallel for schedule(static) if (n > 128)
  for (long i = 0; i < n; ++i) {
    double solid = ball.weight(0, p.radius[i]);
    for (int q = sc.start[i]; q < sc.start[i + 1]; ++q) solid += sc.ordered[q];
    eps[i] = 1 - solid;
  }
}

}  // namespace dem
