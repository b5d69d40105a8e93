#include "forces/fibres.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dem {

void FibreSet::add(const std::vector<std::pair<Index, Vec3>>& ties, const std::vector<double>& rest_lengths, double area_,
                   double modulus_, double strength_) {
  if (ties.size() < 2 || rest_lengths.size() + 1 != ties.size()) throw std::invalid_argument("FibreSet::add: a fibre needs two ties or more, one rest length per segment");
  const int f = static_cast<int>(fibres()), first = static_cast<int>(tie_id.size());
  for (const auto& [id, offset] : ties) tie_id.push_back(id), tie_offset.push_back(offset), tie_slot.push_back(-1);
  first_tie.push_back(static_cast<int>(tie_id.size()));
  area.push_back(area_), modulus.push_back(modulus_), strength.push_back(strength_);
  for (std::size_t s = 0; s < rest_lengths.size(); ++s)
    rest.push_back(rest_lengths[s]), broken.push_back(0), tension.push_back(0), tie_of.push_back(first + static_cast<int>(s)), fibre_of.push_back(f),
        stiffness.push_back(modulus_ * area_ / rest_lengths[s]);
}

void FibreSet::index() {
  tie_of.clear(), fibre_of.clear(), stiffness.clear();
  for (std::size_t f = 0; f < fibres(); ++f)
    for (int t = first_tie[f]; t + 1 < first_tie[f + 1]; ++t) tie_of.push_back(t), fibre_of.push_back(static_cast<int>(f));
  for (std::size_t s = 0; s < rest.size(); ++s) stiffness.push_back(modulus[fibre_of[s]] * area[fibre_of[s]] / rest[s]);
  tension.assign(rest.size(), 0.0);
  tie_slot.assign(tie_id.size(), -1);
}

void FibreSet::resolve(const Particles& p) {
  const std::size_t n = p.size();
  bool current = true;
  for (std::size_t t = 0; t < tie_id.size() && current; ++t) {
    const int s = tie_slot[t];
    current = s >= 0 && static_cast<std::size_t>(s) < n && p.id[s] == tie_id[t];
  }
  if (current) return;
  std::vector<std::pair<Index, int>> by_id(n);
  for (std::size_t k = 0; k < n; ++k) by_id[k] = {p.id[k], static_cast<int>(k)};
  std::sort(by_id.begin(), by_id.end());
  for (std::size_t t = 0; t < tie_id.size(); ++t) {
    const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair<Index, int>{tie_id[t], -1});
    tie_slot[t] = it != by_id.end() && it->first == tie_id[t] ? it->second : -1;
  }
  for (std::size_t s = 0; s < rest.size(); ++s)
    if (tie_slot[tie_of[s]] < 0 || tie_slot[tie_of[s] + 1] < 0) broken[s] = 1, tension[s] = 0;
}

Vec3 FibreSet::span(const Particles& p, const PeriodicBox& box, int a, int b) const {
  const Vec3 centres = box.any() ? box.nearest(p.x[tie_slot[b]] - p.x[tie_slot[a]]) : Vec3(p.x[tie_slot[b]] - p.x[tie_slot[a]]);
  return centres + (tie_offset[b] - tie_offset[a]);
}

double FibreSet::elastic_energy(const Particles& p, const PeriodicBox& box) const {
  double e = 0;
  for (std::size_t s = 0; s < rest.size(); ++s) {
    if (broken[s] || tie_slot[tie_of[s]] < 0) continue;
    // The energy of eq. P60's spring: T^2 / (2 k) = EA/(2 L0) (L - L0)^2.
    const double t = segment_tension(stiffness[s], rest[s], span(p, box, tie_of[s], tie_of[s] + 1).norm());
    e += 0.5 * t * t / stiffness[s];
  }
  return e;
}

double FibreSet::max_stiffness() const {
  double k = 0;
  for (std::size_t s = 0; s < rest.size(); ++s)
    if (!broken[s]) k = std::max(k, stiffness[s]);
  return k;
}

std::size_t FibreSet::broken_count() const { return static_cast<std::size_t>(std::count(broken.begin(), broken.end(), 1)); }

void add_fibre_forces(FibreSet& fibres, const Particles& p, const PeriodicBox& box, std::vector<LoadSum>& force,
                      std::vector<LoadSum>& torque) {
  fibres.resolve(p);
  const long segments = static_cast<long>(fibres.segments());
  for (long s = 0; s < segments; ++s) {
    if (fibres.broken[s]) continue;
    const int a = fibres.tie_of[s], b = a + 1, f = fibres.fibre_of[s];
    const Vec3 d = fibres.span(p, box, a, b);
    const double length = d.norm();
    const double t = segment_tension(fibres.stiffness[s], fibres.rest[s], length);  // eq. P60-P61
    if (t == 0) {  // slack: no force in compression
      fibres.tension[s] = 0;
      continue;
    }
    if (t > fibres.strength[f] * fibres.area[f]) {  // eq. P62: breaks, for ever
      fibres.broken[s] = 1;
      fibres.tension[s] = 0;
      continue;
    }
    fibres.tension[s] = t;
    const Vec3 on_a = (t / length) * d;  // towards b
    const int ia = fibres.tie_slot[a], ib = fibres.tie_slot[b];
    force[ia].v += on_a;
    torque[ia].v += fibres.tie_offset[a].cross(on_a);
    force[ib].v -= on_a;
    torque[ib].v -= fibres.tie_offset[b].cross(on_a);
  }
}

void compute_fibre_tensions(FibreSet& fibres, const Particles& p, const PeriodicBox& box) {
  fibres.resolve(p);
  for (std::size_t s = 0; s < fibres.segments(); ++s) {
    const int a = fibres.tie_of[s];
    const double t = fibres.broken[s] ? 0.0 : segment_tension(fibres.stiffness[s], fibres.rest[s], fibres.span(p, box, a, a + 1).norm());
    fibres.tension[s] = t > fibres.break_force(static_cast<int>(s)) ? 0.0 : t;
  }
}

void rotate_ties(FibreSet& fibres, const Particles& p, double dt) {
  const long ties = static_cast<long>(fibres.ties());
  for (long t = 0; t < ties; ++t) {
    const int k = fibres.tie_slot[t];
    if (k < 0) continue;
    // Rodrigues with the step's rotation vector W = w dt, of angle th = |W|, left unnormalised:
    // r' = r cos(th) + (W x r) sin(th)/th + W (W . r)(1 - cos(th))/th^2.
    const Vec3 turn = p.w[k] * dt;
    const double th2 = turn.squaredNorm();
    if (th2 == 0) continue;
    // The step's angle is tiny (|w| dt ~ 1e-4 at 100 rad/s): up to 1e-3 the series below in th^2,
    // whose first omitted terms are below 1e-19 of the kept ones, are exact to round-off and need
    // no square root, division, sin or cos, which were most of the fibres' cost per step
    // (bench/results/fibres.md).
    double c, sin_over_th, versine_over_th2;  // cos(th), sin(th)/th, (1 - cos(th))/th^2
    if (th2 <= 1e-6) {
      versine_over_th2 = 0.5 * (1 - th2 / 12 * (1 - th2 / 30));
      c = 1 - th2 * versine_over_th2;
      sin_over_th = 1 - th2 / 6 * (1 - th2 / 20);
    } else {
      const double th = std::sqrt(th2);
      c = std::cos(th), sin_over_th = std::sin(th) / th, versine_over_th2 = (1 - c) / th2;
    }
    Vec3& r = fibres.tie_offset[t];
    r = r * c + turn.cross(r) * sin_over_th + turn * (turn.dot(r) * versine_over_th2);
  }
}

}  // namespace dem
