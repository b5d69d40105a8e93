#include "post/stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dem {

Box sphere_box(const Particles& p) {
  Box b{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t k = 0; k < p.size(); ++k) {
    b.lo = b.lo.cwiseMin(p.x[k] - Vec3::Constant(p.radius[k]));
    b.hi = b.hi.cwiseMax(p.x[k] + Vec3::Constant(p.radius[k]));
  }
  return b;
}

double deviatoric_q(const Mat3& s) {
  const Mat3 sym = 0.5 * (s + s.transpose());
  const Mat3 dev = sym - sym.trace() / 3 * Mat3::Identity();
  return std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
}

ParticleStress particle_stress(const Particles& p, const ContactForceSet& c) {
  const std::size_t n = p.size();
  const long np = static_cast<long>(c.pairs()), nw = static_cast<long>(c.walls());
  // Per-particle lists of contact entries, in contact order: 2k = pair k seen from i, 2k+1 from
  // j, 2(np+k) = wall contact k.
  std::vector<long> start(n + 1, 0);
  for (long k = 0; k < np; ++k) ++start[c.pair_i[k] + 1], ++start[c.pair_j[k] + 1];
  for (long k = 0; k < nw; ++k) ++start[c.wall_i[k] + 1];
  for (std::size_t k = 0; k < n; ++k) start[k + 1] += start[k];
  std::vector<long> entry(start[n]);
  std::vector<long> fill(start.begin(), start.end() - 1);
  for (long k = 0; k < np; ++k) entry[fill[c.pair_i[k]]++] = 2 * k, entry[fill[c.pair_j[k]]++] = 2 * k + 1;
  for (long k = 0; k < nw; ++k) entry[fill[c.wall_i[k]]++] = 2 * (np + k);

  ParticleStress s;
  s.moment.assign(n, Mat3::Zero());
  s.contacts.assign(n, 0);
#pragma omp parallel for schedule(static)
  for (long q = 0; q < static_cast<long>(n); ++q) {
    Mat3 m = Mat3::Zero();
    for (long e = start[q]; e < start[q + 1]; ++e) {
      const long code = entry[e], k = code / 2;
      if (k < np) {
        const int i = c.pair_i[k], j = c.pair_j[k];
        const Vec3 l = c.branch(p, k);  // branch vector, i to j
        const double d = l.norm();
        // Contact point x_i + t l, t = (a_i - a_j + d) / (2 d): the middle of the overlap.
        const double t = d > 0 ? (p.radius[i] - p.radius[j] + d) / (2 * d) : 0.5;
        if (code % 2 == 0) m.noalias() += c.pair_force[k] * (t * l).transpose();           // on i, arm t l
        else m.noalias() += (-c.pair_force[k]) * (-(1 - t) * l).transpose();               // on j, arm -(1-t) l
      } else {
        const long w = k - np;
        m.noalias() += c.wall_force[w] * (c.wall_point[w] - p.x[q]).transpose();
      }
    }
    s.moment[q] = m;
    s.contacts[q] = static_cast<int>(start[q + 1] - start[q]);
  }
  return s;
}

FibreBranches fibre_branches(const Particles& p, const PeriodicBox& box, const FibreSet& fibres) {
  FibreBranches out;
  for (std::size_t k = 0; k < fibres.segments(); ++k) {
    const double t = fibres.tension[k];
    if (t == 0) continue;
    const int a = fibres.tie_of[k], b = a + 1, ia = fibres.tie_slot[a], ib = fibres.tie_slot[b];
    out.from.push_back(ia);
    out.to.push_back(ib);
    out.force.push_back(t * fibres.span(p, box, a, b).normalized());
    out.branch.push_back(box.any() ? box.nearest(p.x[ib] - p.x[ia]) : Vec3(p.x[ib] - p.x[ia]));
  }
  return out;
}

void add_fibre_stress(const Particles& p, const PeriodicBox& box, const FibreSet& fibres, ParticleStress& s) {
  const FibreBranches f = fibre_branches(p, box, fibres);
  for (std::size_t k = 0; k < f.size(); ++k) {
    const Mat3 half = 0.5 * f.force[k] * f.branch[k].transpose();  // eq. P64
    s.moment[f.from[k]] += half;
    s.moment[f.to[k]] += half;
  }
}

std::vector<Mat3> particle_stress_tensors(const Particles& p, const ParticleStress& s) {
  std::vector<Mat3> out(p.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < static_cast<long>(p.size()); ++k) out[k] = s.moment[k] / sphere_volume(p.radius[k]);
  return out;
}

std::vector<Mat3> particle_kinetic_stress(const Particles& p) {
  double mass = 0;
  Vec3 mom = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) mass += p.mass[k], mom += p.mass[k] * p.v[k];
  const Vec3 vbar = mass > 0 ? Vec3(mom / mass) : Vec3::Zero();
  std::vector<Mat3> out(p.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < static_cast<long>(p.size()); ++k) {
    const Vec3 dv = p.v[k] - vbar;
    out[k] = -p.mass[k] / sphere_volume(p.radius[k]) * dv * dv.transpose();
  }
  return out;
}

namespace {

// Accumulates the particles of `region` into `bins` slabs along `axis` (bins = 1: the region).
std::vector<BoxAverage> accumulate(const Particles& p, const ParticleStress& s, const Box& region, int axis, int bins,
                                   const std::vector<Vec3>* u) {
  if (bins < 1) throw std::invalid_argument("stress_profile: bins must be at least 1");
  if (u != nullptr && u->size() != p.size()) throw std::invalid_argument("box_average: one displacement per particle needed");
  const double lo = region.lo[axis], width = (region.hi[axis] - region.lo[axis]) / bins;
  std::vector<BoxAverage> out(bins);
  for (int b = 0; b < bins; ++b) {
    out[b].box = region;
    out[b].box.lo[axis] = lo + b * width;
    out[b].box.hi[axis] = b + 1 == bins ? region.hi[axis] : lo + (b + 1) * width;
  }
  std::vector<int> bin(p.size(), -1);
  std::vector<Vec3> mom(bins, Vec3::Zero()), usum(bins, Vec3::Zero());
  std::vector<double> solid(bins, 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!region.contains(p.x[k])) continue;
    const int b = width > 0 ? std::clamp(static_cast<int>(std::floor((p.x[k][axis] - lo) / width)), 0, bins - 1) : 0;
    bin[k] = b;
    BoxAverage& a = out[b];
    ++a.count;
    a.mass += p.mass[k];
    solid[b] += sphere_volume(p.radius[k]);
    mom[b] += p.mass[k] * p.v[k];
    a.contact += s.moment[k];
    if (u != nullptr && (*u)[k].allFinite()) ++a.displaced, usum[b] += (*u)[k];
  }
  for (int b = 0; b < bins; ++b)
    if (out[b].mass > 0) out[b].mean_velocity = mom[b] / out[b].mass;
  for (std::size_t k = 0; k < p.size(); ++k) {  // second pass: fluctuations about each slab's mean
    if (bin[k] < 0) continue;
    const Vec3 dv = p.v[k] - out[bin[k]].mean_velocity;
    out[bin[k]].kinetic.noalias() -= p.mass[k] * dv * dv.transpose();
  }
  for (int b = 0; b < bins; ++b) {
    BoxAverage& a = out[b];
    const double v = a.box.volume();
    a.contact /= v;
    a.kinetic /= v;
    a.solid_fraction = solid[b] / v;
    a.mean_displacement = a.displaced ? Vec3(usum[b] / static_cast<double>(a.displaced)) : Vec3::Constant(std::nan(""));
  }
  return out;
}

}  // namespace

BoxAverage box_average(const Particles& p, const ParticleStress& s, const Box& box, const std::vector<Vec3>* u) {
  return accumulate(p, s, box, 2, 1, u)[0];
}

std::vector<BoxAverage> stress_profile(const Particles& p, const ParticleStress& s, const Box& region, int axis, int bins,
                                       const std::vector<Vec3>* u) {
  return accumulate(p, s, region, axis, bins, u);
}

}  // namespace dem
