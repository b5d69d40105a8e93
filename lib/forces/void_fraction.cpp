#include "forces/void_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>

#include "core/error.hpp"
#include "core/lucy_kernel.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

LucyBall::LucyBall(double c)
    : c_(c), amp_(LucyKernel(c / std::sqrt(12.0)).amplitude()), f2_(-6 / (c * c)), f3_(8 / (c * c * c)), f4_(-3 / (c * c * c * c)),
      ball_(4 * std::numbers::pi / 3 * amp_), l0_(6 * f2_ / 10), l1_(12 * f3_ / 10), l2_(20 * f4_ / 10), m0_(120 * f4_ / 280),
      m1_(24 * f3_ / 280), hc0_(c * c * c * c * (-1.0 / 4 + c * c * (-f2_ / 6 + c * (-f3_ / 7 - c * f4_ / 8)))),
      hc1_(c * c * (1.0 / 2 + c * c * (f2_ / 4 + c * (f3_ / 5 + c * f4_ / 6)))), hc2_(c * c * c * (1.0 / 3 + c * c * (f2_ / 5 + c * (f3_ / 6 + c * f4_ / 7)))) {}

double LucyBall::shells(double s, double a) const {
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
    // At t1 = c (the ball cut by the support's edge: most calls) H is linear in g1 and g2, its
    // coefficients the update's: H(c) = hc0 + hc1 g1 + hc2 g2.
    w += std::numbers::pi / s * ((t1 == c_ ? hc0_ + hc1_ * g1 + hc2_ * g2 : H(t1)) - H(t0));
  }
  return amp_ * w;
}

double ball_weight(double s, double a, double c) { return LucyBall(c).weight(s, a); }

namespace {

// The grains of the cell runs (places [run[0], run[1]) in scratch order) that the kernel of the
// particle at place m reaches, |x_q - x_m| < c + a_q, visited in order: visit(q, |x_q - x_m|).
template <class Visit>
void each_reached(const VoidFractionScratch& sc, const PeriodicBox& box, int m, const int (*runs)[2], int count, Visit&& visit) {
  const Vec3 xm = sc.x[m];
  const bool periodic = box.any();
  for (int r = 0; r < count; ++r)
    for (int q = runs[r][0]; q < runs[r][1]; ++q) {
      const Vec3 d = periodic ? box.nearest(sc.x[q] - xm) : Vec3(sc.x[q] - xm);
      const double s2 = (d.x() * d.x() + d.y() * d.y()) + d.z() * d.z();  // each_reached_four's order
      if (s2 < sc.reach2[q] && q != m) visit(q, std::sqrt(s2));
    }
}

#ifdef DEM_SIMD_LOOPS
// each_reached without periodic axes, four places at a time: each distance by the same operations
// in the same order as each_reached's (so both find exactly the same grains, in the same order,
// and pass the same bits). The arrays hold 3 places more than there are grains.
template <class Visit>
DEM_AVX2 void each_reached_four(const VoidFractionScratch& sc, int m, const int (*runs)[2], int count, Visit&& visit) {
  using lanes::Lanes4;
  const Vec3 xm = sc.x[m];
  const Lanes4 x0 = simd::broadcast(xm.x()), x1 = simd::broadcast(xm.y()), x2 = simd::broadcast(xm.z());
  alignas(32) double s[4];
  for (int r = 0; r < count; ++r)
    for (int q = runs[r][0]; q < runs[r][1]; q += 4) {
      const Lanes4 d0 = simd::load(sc.x0.data() + q) - x0, d1 = simd::load(sc.x1.data() + q) - x1, d2 = simd::load(sc.x2.data() + q) - x2;
      const Lanes4 s2 = (d0 * d0 + d1 * d1) + d2 * d2;
      int hits = simd::bits(lanes::less(s2, simd::load(sc.reach2.data() + q)));
      hits &= (1 << std::min(4, runs[r][1] - q)) - 1;
      if (m >= q && m < q + 4) hits &= ~(1 << (m - q));
      if (!hits) continue;
      simd::store_aligned(s, lanes::root(s2));
      for (; hits; hits &= hits - 1) {
        const int l = __builtin_ctz(hits);
        visit(q + l, s[l]);
      }
    }
}

// Particle m's sum (P70) with each_reached_four.
DEM_AVX2 double solid_four(const VoidFractionScratch& sc, const LucyBall& ball, int m, const int (*runs)[2], int count) {
  double solid = ball.weight(0, sc.radius[m]);
  each_reached_four(sc, m, runs, count, [&](int q, double s) { solid += ball.weight(s, sc.radius[q]); });
  return solid;
}
#endif

}  // namespace

void void_fractions(const Particles& p, const PeriodicBox& box, double c, VoidFractionScratch& sc, std::vector<double>& eps) {
  const int n = static_cast<int>(p.size());
  eps.resize(n);
  if (n == 0) return;
  const LucyBall ball(c);
  Vec3 lo = p.x[0], hi = lo;
  double amax = 0;
  for (int k = 0; k < n; ++k) lo = lo.cwiseMin(p.x[k]), hi = hi.cwiseMax(p.x[k]), amax = std::max(amax, p.radius[k]);
  // The kernel of particle i reaches grain j while |x_i - x_j| < c + a_j <= c + amax: with cells of
  // edge >= c + amax, j lies in i's cell or one of its 26 neighbours. A period holds a whole number
  // of cells (at least 3, so that the neighbours are distinct cells); an open axis has an empty
  // cell at each end. Cells widened while there are more than 2 n + 27 (a grain flown far away).
  long dims[3], pad[3];
  double origin[3], edge[3];
  for (double e = c + amax;; e *= 1.26) {
    long total = 1;
    for (int d = 0; d < 3; ++d) {
      pad[d] = box.axis[d] ? 0 : 1;
      dims[d] = box.axis[d] ? std::max(1L, static_cast<long>(std::floor(box.length(d) / e)))
                            : static_cast<long>(std::floor((hi[d] - lo[d]) / e)) + 3;
      edge[d] = box.axis[d] ? box.length(d) / dims[d] : e;
      origin[d] = box.axis[d] ? box.lo[d] : lo[d] - e;
      total *= dims[d];
    }
    if (total <= 2L * n + 27) break;
  }
  for (int d = 0; d < 3; ++d)
    if (dims[d] < 3) {
      std::ostringstream m;
      m << "periodic boundaries: the period along " << "xyz"[d] << " (" << box.length(d) << " m) must hold at least 3 cells of "
        << c + amax << " m (void_cutoff plus the largest radius) for the fluid's void fractions: widen the period";
      throw InputError(m.str());
    }
  auto coord = [&](const Vec3& x, int d) {
    return std::clamp(static_cast<long>(std::floor((x[d] - origin[d]) / edge[d])), pad[d], dims[d] - 1 - pad[d]);
  };
  // Each cell's grains as one run, in id order (a counting sort by cell of the grains in id order).
  const long ncell = dims[0] * dims[1] * dims[2];
  sc.by_id.resize(n);
  std::iota(sc.by_id.begin(), sc.by_id.end(), 0);
  std::sort(sc.by_id.begin(), sc.by_id.end(), [&](int a, int b) { return p.id[a] < p.id[b]; });
  sc.cell_of.resize(n);
  sc.cell_first.assign(ncell + 1, 0);
  for (int k = 0; k < n; ++k) {
    sc.cell_of[k] = static_cast<int>((coord(p.x[k], 2) * dims[1] + coord(p.x[k], 1)) * dims[0] + coord(p.x[k], 0));
    ++sc.cell_first[sc.cell_of[k] + 1];
  }
  for (long q = 0; q < ncell; ++q) sc.cell_first[q + 1] += sc.cell_first[q];
  // 3 places more, never reached (the four-wide distances read up to 3 past a run's end).
  sc.slot.resize(n), sc.x.resize(n), sc.radius.resize(n), sc.reach2.assign(n + 3, -1);
  sc.x0.assign(n + 3, 0), sc.x1.assign(n + 3, 0), sc.x2.assign(n + 3, 0);
  for (const int k : sc.by_id) {
    const int at = sc.cell_first[sc.cell_of[k]]++;
    sc.slot[at] = k, sc.x[at] = p.x[k], sc.radius[at] = p.radius[k], sc.reach2[at] = (c + p.radius[k]) * (c + p.radius[k]);
    sc.x0[at] = p.x[k].x(), sc.x1[at] = p.x[k].y(), sc.x2[at] = p.x[k].z();
  }
  std::copy_backward(sc.cell_first.begin(), sc.cell_first.end() - 1, sc.cell_first.end());  // the fill moved each start to the next's
  sc.cell_first[0] = 0;
  // Each particle's sum (P70): its own ball, then the 27 cells around in the order (z, y, x) of
  // their offsets, each cell's grains in id order; every sum by one thread.
  const bool periodic = box.any();
#ifdef DEM_SIMD_LOOPS
  const bool four = simd_loops_on() && !periodic;
#endif
#pragma omp parallel for schedule(dynamic, 16) if (n > 128)
  for (long cell = 0; cell < ncell; ++cell) {
    if (sc.cell_first[cell] == sc.cell_first[cell + 1]) continue;
    const long at[3] = {cell % dims[0], (cell / dims[0]) % dims[1], cell / (dims[0] * dims[1])};
    // The neighbours' runs of places, those that follow one another joined (along x without a
    // period: three cells, one run).
    int runs[27][2], count = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          long nb[3] = {at[0] + dx, at[1] + dy, at[2] + dz};
          for (int d = 0; d < 3; ++d) nb[d] = (nb[d] + dims[d]) % dims[d];  // wraps a period; an open axis's padding keeps it on the grid
          const long q = (nb[2] * dims[1] + nb[1]) * dims[0] + nb[0];
          if (count > 0 && runs[count - 1][1] == sc.cell_first[q]) runs[count - 1][1] = sc.cell_first[q + 1];
          else runs[count][0] = sc.cell_first[q], runs[count++][1] = sc.cell_first[q + 1];
        }
    for (int m = sc.cell_first[cell]; m < sc.cell_first[cell + 1]; ++m) {
#ifdef DEM_SIMD_LOOPS
      if (four) {
        eps[sc.slot[m]] = 1 - solid_four(sc, ball, m, runs, count);
        continue;
      }
#endif
      double solid = ball.weight(0, sc.radius[m]);
      each_reached(sc, box, m, runs, count, [&](int q, double s) { solid += ball.weight(s, sc.radius[q]); });
      eps[sc.slot[m]] = 1 - solid;
    }
  }
}

}  // namespace dem
