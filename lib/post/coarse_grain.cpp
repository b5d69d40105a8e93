#include "post/coarse_grain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "post/kernel.hpp"

namespace dem {

GridSpec grid_covering(const Box& box, double cell) {
  if (!(cell > 0)) throw std::invalid_argument("grid_covering: the cell size must be positive");
  GridSpec g;
  g.origin = box.lo;
  g.cell = cell;
  for (int a = 0; a < 3; ++a) g.n[a] = static_cast<long>(std::ceil((box.hi[a] - box.lo[a]) / cell - 1e-9)) + 1;
  return g;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Items (particles or contacts) bucketed by the first node plane (along z) they reach, so that a
// plane finds its items by scanning the buckets of the `span` planes below it, in a fixed order.
struct PlaneBuckets {
  std::vector<long> start;  // bucket k: items order[start[k] .. start[k+1])
  std::vector<long> order;
  std::vector<long> last;   // last plane each item reaches
  long span = 0;            // largest last - first

  PlaneBuckets(const std::vector<double>& zmin, const std::vector<double>& zmax, const GridSpec& g) {
    const long nz = g.n[2], n = static_cast<long>(zmin.size());
    std::vector<long> first(n);
    last.resize(n);
    start.assign(nz + 1, 0);
    for (long q = 0; q < n; ++q) {
      first[q] = std::max(0L, static_cast<long>(std::ceil((zmin[q] - g.origin[2]) / g.cell)));
      last[q] = std::min(nz - 1, static_cast<long>(std::floor((zmax[q] - g.origin[2]) / g.cell)));
      if (first[q] > last[q]) continue;  // reaches no plane of the grid
      ++start[first[q] + 1];
      span = std::max(span, last[q] - first[q]);
    }
    for (long k = 0; k < nz; ++k) start[k + 1] += start[k];
    order.resize(start[nz]);
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (long q = 0; q < n; ++q)
      if (first[q] <= last[q]) order[fill[first[q]]++] = q;
  }

  // Calls f(q) for every item reaching plane k, in bucket then item order.
  template <class F>
  void for_plane(long k, F&& f) const {
    for (long b = std::max(0L, k - span); b <= k; ++b)
      for (long e = start[b]; e < start[b + 1]; ++e)
        if (last[order[e]] >= k) f(order[e]);
  }
};

// What one node of a plane gathers from the particles.
struct NodeSums {
  double rho = 0, nu = 0;
  Vec3 mom = Vec3::Zero();
  // Weighted least-squares sums (weight m phi, offsets d = x_p - r) of the displacement fit.
  double W = 0;
  Vec3 D = Vec3::Zero(), U = Vec3::Zero();
  Mat3 DD = Mat3::Zero(), UD = Mat3::Zero();
};

}  // namespace

GridFields coarse_grain(const Particles& p, const ContactForceSet& c, const std::vector<Vec3>* u, const GridSpec& grid, double width,
                        const FibreBranches* fibres) {
  if (!(width > 0)) throw std::invalid_argument("coarse_grain: the kernel width must be positive");
  if (!(grid.cell > 0) || grid.n[0] < 1 || grid.n[1] < 1 || grid.n[2] < 1) throw std::invalid_argument("coarse_grain: empty grid");
  if (u != nullptr && u->size() != p.size()) throw std::invalid_argument("coarse_grain: one displacement per particle needed");
  const LucyKernel kern(width);
  const double cut = kern.cutoff(), cut2 = cut * cut, h = grid.cell;
  const long nx = grid.n[0], ny = grid.n[1], nz = grid.n[2];
  const Vec3 o = grid.origin;
  const std::size_t nodes = grid.nodes();

  GridFields out;
  out.grid = grid;
  out.width = width;
  out.density.assign(nodes, 0.0);
  out.solid_fraction.assign(nodes, 0.0);
  out.velocity.assign(nodes, Vec3::Zero());
  out.contact_stress.assign(nodes, Mat3::Zero());
  out.kinetic_stress.assign(nodes, Mat3::Zero());
  if (u != nullptr) {
    out.displacement.assign(nodes, Vec3::Constant(kNaN));
    out.displacement_gradient.assign(nodes, Mat3::Constant(kNaN));
  }

  // Particles reach planes within the cut-off of their centre.
  const long np = static_cast<long>(p.size());
  std::vector<double> zmin(np), zmax(np);
  for (long q = 0; q < np; ++q) zmin[q] = p.x[q][2] - cut, zmax[q] = p.x[q][2] + cut;
  const PlaneBuckets pb(zmin, zmax, grid);

  // Contacts: segments x0 + s l, s in [0, 1], carrying f (x) l; after the pairs and the walls,
  // the fibres' segments, each as a pair contact (eq. P64).
  const long ncp = static_cast<long>(c.pairs()), ncw = ncp + static_cast<long>(c.walls());
  const long nc = ncw + (fibres != nullptr ? static_cast<long>(fibres->size()) : 0L);
  std::vector<Vec3> x0(nc), l(nc);
  std::vector<Mat3> fl(nc);
  zmin.resize(nc);
  zmax.resize(nc);
  for (long k = 0; k < nc; ++k) {
    Vec3 f;
    if (k < ncp) {
      x0[k] = p.x[c.pair_i[k]];
      l[k] = c.branch(p, k);
      f = c.pair_force[k];
    } else if (k < ncw) {
      const long w = k - ncp;
      x0[k] = p.x[c.wall_i[w]];
      l[k] = c.wall_point[w] - x0[k];
      f = c.wall_force[w];
    } else {
      const long s = k - ncw;
      x0[k] = p.x[fibres->from[s]];
      l[k] = fibres->branch[s];
      f = fibres->force[s];
    }
    fl[k] = f * l[k].transpose();
    zmin[k] = std::min(x0[k][2], x0[k][2] + l[k][2]) - cut;
    zmax[k] = std::max(x0[k][2], x0[k][2] + l[k][2]) + cut;
  }
  const PlaneBuckets cb(zmin, zmax, grid);

  // Node index ranges within reach of [a - r, b + r] along axis `ax` (empty when lo > hi).
  auto range = [&](int ax, double a, double b) {
    const long n = grid.n[ax];
    const long lo = std::max(0L, static_cast<long>(std::ceil((a - o[ax]) / h)));
    const long hi = std::min(n - 1, static_cast<long>(std::floor((b - o[ax]) / h)));
    return std::make_pair(lo, hi);
  };

#pragma omp parallel
  {
    std::vector<NodeSums> sums;
    std::vector<Mat3> kin;
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < nz; ++k) {
      const double zk = o[2] + h * k;
      sums.assign(static_cast<std::size_t>(nx * ny), NodeSums{});
      kin.assign(static_cast<std::size_t>(nx * ny), Mat3::Zero());
      const std::size_t base = static_cast<std::size_t>(nx * ny) * k;

      // Visits the nodes of this plane within the cut-off of particle q: f(node, phi, d = x_q - r).
      auto each_node = [&](long q, auto&& f) {
        const Vec3& x = p.x[q];
        const double dz = zk - x[2];
        if (dz * dz >= cut2) return;
        const double reach = std::sqrt(cut2 - dz * dz);
        const auto [i0, i1] = range(0, x[0] - reach, x[0] + reach);
        const auto [j0, j1] = range(1, x[1] - reach, x[1] + reach);
        for (long j = j0; j <= j1; ++j) {
          const double dy = o[1] + h * j - x[1];
          for (long i = i0; i <= i1; ++i) {
            const double dx = o[0] + h * i - x[0];
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= cut2) continue;
            f(j * nx + i, kern.value_r2(r2), Vec3(-dx, -dy, -dz));
          }
        }
      };

      // Particles, first pass: density, solid fraction, momentum, displacement-fit sums.
      pb.for_plane(k, [&](long q) {
        const double m = p.mass[q], vol = sphere_volume(p.radius[q]);
        const Vec3& v = p.v[q];
        const bool fit = u != nullptr && (*u)[q].allFinite();
        each_node(q, [&](long node, double phi, const Vec3& d) {
          NodeSums& s = sums[node];
          s.rho += m * phi;
          s.nu += vol * phi;
          s.mom += (m * phi) * v;
          if (fit) {
            const double w = m * phi;
            s.W += w;
            s.D += w * d;
            s.U += w * (*u)[q];
            s.DD.noalias() += (w * d) * d.transpose();
            s.UD.noalias() += (w * (*u)[q]) * d.transpose();
          }
        });
      });
      for (long node = 0; node < nx * ny; ++node) {
        const NodeSums& s = sums[node];
        out.density[base + node] = s.rho;
        out.solid_fraction[base + node] = s.nu;
        if (s.rho > 0) out.velocity[base + node] = s.mom / s.rho;
      }
      // Second pass: kinetic stress from the fluctuations about the node's mean velocity.
      pb.for_plane(k, [&](long q) {
        const double m = p.mass[q];
        each_node(q, [&](long node, double phi, const Vec3&) {
          const Vec3 dv = p.v[q] - out.velocity[base + node];
          kin[node].noalias() -= (m * phi) * dv * dv.transpose();
        });
      });
      for (long node = 0; node < nx * ny; ++node) out.kinetic_stress[base + node] = kin[node];

      // Displacement fit: u ~ a + G (x - r); a and G from the weighted covariances.
      if (u != nullptr) {
        const double min_spread2 = 0.01 * width * width;  // (0.1 w)^2
        for (long node = 0; node < nx * ny; ++node) {
          const NodeSums& s = sums[node];
          if (!(s.W > 0)) continue;
          const Vec3 dbar = s.D / s.W, ubar = s.U / s.W;
          const Mat3 cxx = s.DD / s.W - dbar * dbar.transpose();
          const Mat3 cux = s.UD / s.W - ubar * dbar.transpose();
          Eigen::SelfAdjointEigenSolver<Mat3> eig;
          eig.computeDirect(cxx, Eigen::EigenvaluesOnly);
          if (!(eig.eigenvalues()[0] >= min_spread2)) continue;
          const Mat3 G = cxx.llt().solve(cux.transpose()).transpose();  // cux cxx^-1 (cxx symmetric)
          const Mat3 A = Mat3::Identity() - G;                            // dX/dx
          Eigen::FullPivLU<Mat3> lu(A);
          if (!lu.isInvertible()) continue;
          out.displacement[base + node] = ubar - G * dbar;
          out.displacement_gradient[base + node] = lu.inverse() - Mat3::Identity();
        }
      }

      // Contacts: the kernel integrated along each branch vector.
      std::vector<Mat3>& sig = kin;  // reuse the buffer
      std::fill(sig.begin(), sig.end(), Mat3::Zero());
      cb.for_plane(k, [&](long q) {
        const Vec3& a = x0[q];
        const Vec3& lq = l[q];
        const LucySegment segment(kern, lq);
        double s0 = 0, s1 = 1;  // the part of the segment within the cut-off of this plane
        if (lq[2] != 0) {
          double sa = (zk - cut - a[2]) / lq[2], sb = (zk + cut - a[2]) / lq[2];
          if (sa > sb) std::swap(sa, sb);
          s0 = std::max(0.0, sa), s1 = std::min(1.0, sb);
          if (s0 > s1) return;
        } else if (std::abs(zk - a[2]) >= cut) {
          return;
        }
        const auto [i0, i1] = range(0, std::min(a[0] + s0 * lq[0], a[0] + s1 * lq[0]) - cut, std::max(a[0] + s0 * lq[0], a[0] + s1 * lq[0]) + cut);
        const auto [j0, j1] = range(1, std::min(a[1] + s0 * lq[1], a[1] + s1 * lq[1]) - cut, std::max(a[1] + s0 * lq[1], a[1] + s1 * lq[1]) + cut);
        for (long j = j0; j <= j1; ++j)
          for (long i = i0; i <= i1; ++i) {
            const Vec3 d(o[0] + h * i - a[0], o[1] + h * j - a[1], zk - a[2]);
            const double w = segment.integral(d);
            if (w > 0) sig[j * nx + i].noalias() += w * fl[q];
          }
      });
      for (long node = 0; node < nx * ny; ++node) out.contact_stress[base + node] = sig[node];
    }
  }
  return out;
}

}  // namespace dem
