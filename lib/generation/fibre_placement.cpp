#include "generation/fibre_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>

namespace dem {

FibrePlacement place_fibres(const Particles& p, const FibreSpec& spec, FibreSet& out) {
  FibrePlacement r;
  if (p.size() < 2) return r;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t k = 0; k < p.size(); ++k)
    lo = lo.cwiseMin(p.x[k] - Vec3::Constant(p.radius[k])), hi = hi.cwiseMax(p.x[k] + Vec3::Constant(p.radius[k]));
  r.box_volume = (hi - lo).prod();
  const double area = std::numbers::pi * spec.diameter * spec.diameter / 4;
  const double target_volume = spec.volume_fraction * r.box_volume;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::tuple<double, Index, std::size_t>> hits;  // (position along the fibre, id, slot)
  std::vector<std::pair<Index, Vec3>> ties;
  std::vector<double> rest;
  long misses = 0;
  while (spec.count > 0 ? static_cast<long>(r.placed) < spec.count : r.volume < target_volume) {
    Vec3 c;
    for (int d = 0; d < 3; ++d) c[d] = lo[d] + (hi[d] - lo[d]) * unit(rng);
    const double cz = 2 * unit(rng) - 1, phi = 2 * std::numbers::pi * unit(rng), sz = std::sqrt(1 - cz * cz);
    const Vec3 u(sz * std::cos(phi), sz * std::sin(phi), cz);
    const double length = spec.length_min + (spec.length_max - spec.length_min) * unit(rng);
    const Vec3 start = c - 0.5 * length * u;
    hits.clear();
    for (std::size_t k = 0; k < p.size(); ++k) {  // in storage order; sorted by (s, id) below
      const double s = std::clamp((p.x[k] - start).dot(u), 0.0, length);
      const Vec3 q = start + s * u;
      if ((q - p.x[k]).squaredNorm() < p.radius[k] * p.radius[k]) hits.emplace_back(s, p.id[k], k);
    }
    if (hits.size() < 2) {
      ++r.redrawn;
      if (++misses >= 1000)
        throw std::runtime_error("fibres: 1000 draws in a row met fewer than two particles each (fibres of length " +
                                 std::to_string(spec.length_max) + " m too short for the sample?)");
      continue;
    }
    misses = 0;
    std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) {
      return std::get<0>(a) < std::get<0>(b) || (std::get<0>(a) == std::get<0>(b) && std::get<1>(a) < std::get<1>(b));
    });
    ties.clear(), rest.clear();
    std::size_t j = 0;  // the slot of the last tie
    for (std::size_t h = 0; h < hits.size(); ++h) {
      const std::size_t k = std::get<2>(hits[h]);
      const Vec3 offset = (start + std::get<0>(hits[h]) * u) - p.x[k];
      if (h > 0) {
        // The rest length as the force loop measures the span (FibreSet::span): no stretch at placement.
        const double l = ((p.x[k] - p.x[j]) + (offset - ties.back().second)).norm();
        // A tie closer to the last than half the smaller radius is skipped (eq. P63): a segment
        // that short would be stiffer than EA / (a/2) and set the time step.
        if (!(l >= 0.5 * std::min(p.radius[k], p.radius[j]))) continue;
        rest.push_back(l);
      }
      ties.emplace_back(std::get<1>(hits[h]), offset);
      j = k;
    }
    if (ties.size() < 2) {
      ++r.redrawn;
      continue;
    }
    out.add(ties, rest, area, spec.youngs_modulus, spec.tensile_strength);
    ++r.placed;
    r.ties += ties.size();
    r.volume += area * length;
  }
  return r;
}

}  // namespace dem
