#include "forces/fibres.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "simd/lanes.hpp"
#include "simd/lanes_avx2.hpp"
#include "simd/layout.hpp"
#include "simd/memory.hpp"
#include "simd/simd.hpp"

namespace dem {

void FibreSet::add(const std::vector<std::pair<Index, Vec3>>& ties, const std::vector<double>& rest_lengths, double area_,
                   double modulus_, double strength_) {
  if (ties.size() < 2 || rest_lengths.size() + 1 != ties.size()) throw std::invalid_argument("FibreSet::add: a fibre needs two ties or more, one rest length per segment");
  const int f = static_cast<int>(fibres()), first = static_cast<int>(tie_id.size());
  for (const auto& [id, offset] : ties) tie_id.push_back(id), tie_offset.push_back(offset), tie_slot.push_back(kNotFound);
  first_tie.push_back(static_cast<int>(tie_id.size()));
  area.push_back(area_), modulus.push_back(modulus_), strength.push_back(strength_);
  for (std::size_t s = 0; s < rest_lengths.size(); ++s)
    rest.push_back(rest_lengths[s]), broken.push_back(0), tension.push_back(0), tie_of.push_back(first + static_cast<int>(s)), fibre_of.push_back(f),
        stiffness.push_back(modulus_ * area_ / rest_lengths[s]), breaking.push_back(strength_ * area_);
}

void FibreSet::index() {
  tie_of.clear(), fibre_of.clear(), stiffness.clear(), breaking.clear();
  for (std::size_t f = 0; f < fibres(); ++f)
    for (int t = first_tie[f]; t + 1 < first_tie[f + 1]; ++t) tie_of.push_back(t), fibre_of.push_back(static_cast<int>(f));
  for (std::size_t s = 0; s < rest.size(); ++s)
    stiffness.push_back(modulus[fibre_of[s]] * area[fibre_of[s]] / rest[s]), breaking.push_back(strength[fibre_of[s]] * area[fibre_of[s]]);
  tension.assign(rest.size(), 0.0);
  tie_slot.assign(tie_id.size(), kNotFound);
}

void FibreSet::resolve(const Particles& p) {
  const std::size_t n = p.size();
  const Index* id = p.id.data();
  bool current = true;
  for (std::size_t t = 0; t < tie_id.size(); ++t) {
    if (tie_slot[t] == kGone) continue;
    const std::size_t s = static_cast<unsigned>(tie_slot[t]);  // kNotFound beyond any n
    if (s >= n || id[s] != tie_id[t]) {
      current = false;
      break;
    }
  }
  if (current) return;
  ++searches;
  std::vector<std::pair<Index, int>> by_id(n);
  for (std::size_t k = 0; k < n; ++k) by_id[k] = {p.id[k], static_cast<int>(k)};
  std::sort(by_id.begin(), by_id.end());
  for (std::size_t t = 0; t < tie_id.size(); ++t) {
    const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair<Index, int>{tie_id[t], -1});
    tie_slot[t] = it != by_id.end() && it->first == tie_id[t] ? it->second : kGone;
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

namespace {

using lanes::Triple;

// Segment s, its ties' slots resolved (eq. P60-P62): nothing if broken; else its tension into
// fibres.tension, and T e on a's particle at its tie point, -T e on b's, each with its torque
// offset x force, added in this order.
inline void pull_segment(FibreSet& fibres, const Particles& p, const PeriodicBox& box, long s, std::vector<LoadSum>& force,
                         std::vector<LoadSum>& torque) {
  if (fibres.broken[s]) return;
  const int a = fibres.tie_of[s], b = a + 1;
  const Vec3 d = fibres.span(p, box, a, b);
  const double length = d.norm();
  const double t = segment_tension(fibres.stiffness[s], fibres.rest[s], length);  // eq. P60-P61
  if (t > fibres.breaking[s]) {  // eq. P62: breaks, for ever
    fibres.broken[s] = 1;
    fibres.tension[s] = 0;
    return;
  }
  fibres.tension[s] = t;
  if (t == 0) return;  // slack: no force in compression
  const Vec3 on_a = (t / length) * d;  // towards b
  const int ia = fibres.tie_slot[a], ib = fibres.tie_slot[b];
  force[ia].v += on_a;
  torque[ia].v += fibres.tie_offset[a].cross(on_a);
  force[ib].v -= on_a;
  torque[ib].v -= fibres.tie_offset[b].cross(on_a);
}

#ifdef DEM_SIMD_LOOPS
using lanes::Lanes4;

// Four segments at a time (simd.hpp: the same operations in the same order as pull_segment, and
// the loads added to the particles one segment after the other, so the same bits). A four with a
// broken segment, or one that breaks now, goes one by one. Without periodic boundaries (`box` has
// none: FibreSet::span's plain difference). Returns the first segment not done.
DEM_AVX2 long pull_four_at_a_time(FibreSet& fibres, const Particles& p, const PeriodicBox& box, std::vector<LoadSum>& force,
                                   std::vector<LoadSum>& torque) {
  const long segments = static_cast<long>(fibres.segments());
  const Lanes4 zero = simd::broadcast(0.0);
  const Vec3 *x = p.x.data(), *offset = fibres.tie_offset.data();
  const int *tie_of = fibres.tie_of.data(), *slot = fibres.tie_slot.data();
  long s = 0;
  for (; s + 4 <= segments; s += 4) {
    std::uint32_t any_broken;
    std::memcpy(&any_broken, fibres.broken.data() + s, 4);
    const int a[4] = {tie_of[s], tie_of[s + 1], tie_of[s + 2], tie_of[s + 3]};
    if (any_broken) {
      for (long u = s; u < s + 4; ++u) pull_segment(fibres, p, box, u, force, torque);
      continue;
    }
    const int ia[4] = {slot[a[0]], slot[a[1]], slot[a[2]], slot[a[3]]};
    const int ib[4] = {slot[a[0] + 1], slot[a[1] + 1], slot[a[2] + 1], slot[a[3] + 1]};
    const Triple<Lanes4> oa = simd::load_four(offset, a[0], a[1], a[2], a[3]);
    const Triple<Lanes4> ob = simd::load_four(offset, a[0] + 1, a[1] + 1, a[2] + 1, a[3] + 1);
    // FibreSet::span's order: the centres' difference, then the offsets'.
    const Triple<Lanes4> d = (simd::load_four(x, ib[0], ib[1], ib[2], ib[3]) - simd::load_four(x, ia[0], ia[1], ia[2], ia[3])) + (ob - oa);
    const Lanes4 length = lanes::root(lanes::dot(d, d));
    const Lanes4 t = segment_tension(simd::load(fibres.stiffness.data() + s), simd::load(fibres.rest.data() + s), length);  // eq. P60-P61
    if (simd::bits(lanes::less(simd::load(fibres.breaking.data() + s), t))) {  // eq. P62: one breaks
      for (long u = s; u < s + 4; ++u) pull_segment(fibres, p, box, u, force, torque);
      continue;
    }
    simd::store(fibres.tension.data() + s, t);
    const int pulling = simd::bits(lanes::less(zero, t));  // pull_segment's t != 0
    if (!pulling) continue;  // all four slack
    const Triple<Lanes4> on_a = (t / length) * d;
    Lanes4 f[4], ta[4], tb[4];
    simd::per_lane(on_a, f), simd::per_lane(lanes::cross(oa, on_a), ta), simd::per_lane(lanes::cross(ob, on_a), tb);
    for (int l = 0; l < 4; ++l) {
      if (!(pulling >> l & 1)) continue;
      double *fa = force[ia[l]].v.data(), *qa = torque[ia[l]].v.data(), *fb = force[ib[l]].v.data(), *qb = torque[ib[l]].v.data();
      simd::store(fa, simd::load(fa) + f[l]);  // LoadSum: four doubles, the fourth never read
      simd::store(qa, simd::load(qa) + ta[l]);
      simd::store(fb, simd::load(fb) - f[l]);
      simd::store(qb, simd::load(qb) - tb[l]);
    }
  }
  return s;
}
#endif

}  // namespace

void add_fibre_forces(FibreSet& fibres, const Particles& p, const PeriodicBox& box, std::vector<LoadSum>& force,
                      std::vector<LoadSum>& torque) {
  fibres.resolve(p);
  const long segments = static_cast<long>(fibres.segments());
  long s = 0;
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on() && !box.any()) s = pull_four_at_a_time(fibres, p, box, force, torque);
#endif
  for (; s < segments; ++s) pull_segment(fibres, p, box, s, force, torque);
}

void compute_fibre_tensions(FibreSet& fibres, const Particles& p, const PeriodicBox& box) {
  fibres.resolve(p);
  for (std::size_t s = 0; s < fibres.segments(); ++s) {
    const int a = fibres.tie_of[s];
    const double t = fibres.broken[s] ? 0.0 : segment_tension(fibres.stiffness[s], fibres.rest[s], fibres.span(p, box, a, a + 1).norm());
    fibres.tension[s] = t > fibres.break_force(static_cast<int>(s)) ? 0.0 : t;
  }
}

namespace {

// Rodrigues with the step's rotation vector W = w dt of angle th = |W|, left unnormalised
// (physics.md, Fibres, "Ties are fixed in the particle"):
// r' = r cos(th) + (W x r) sin(th)/th + W (W . r)(1 - cos(th))/th^2.
// The step's angle is tiny (|w| dt ~ 1e-4 at 100 rad/s): up to 1e-3 (th^2 <= kSeriesLimit) the
// series of cos(th), sin(th)/th and (1 - cos(th))/th^2 in th^2 below, whose first omitted terms are
// below 1e-19 of the kept ones, are exact to round-off and need no square root, division, sin or
// cos; written once for one tie or four (simd/lanes.hpp).
constexpr double kSeriesLimit = 1e-6;
template <class L>
[[gnu::always_inline]] inline Triple<L> turned_by_series(const Triple<L>& r, const Triple<L>& turn, const L& th2) {
  const L versine_over_th2 = L(0.5) * (L(1.0) - th2 / L(12.0) * (L(1.0) - th2 / L(30.0)));
  const L c = L(1.0) - th2 * versine_over_th2;
  const L sin_over_th = L(1.0) - th2 / L(6.0) * (L(1.0) - th2 / L(20.0));
  return (r * c + lanes::cross(turn, r) * sin_over_th) + turn * (lanes::dot(turn, r) * versine_over_th2);
}

inline void turn_tie(FibreSet& fibres, const Particles& p, double dt, long t) {
  const int k = fibres.tie_slot[t];
  if (k < 0) return;
  const Triple<double> turn = lanes::triple(p.w[k]) * dt;
  const double th2 = lanes::dot(turn, turn);
  if (th2 == 0) return;
  Vec3& r = fibres.tie_offset[t];
  if (th2 <= kSeriesLimit) {
    r = lanes::vec3(turned_by_series(lanes::triple(r), turn, th2));
    return;
  }
  const double th = std::sqrt(th2), c = std::cos(th), sin_over_th = std::sin(th) / th, versine_over_th2 = (1 - c) / th2;
  const Vec3 w = lanes::vec3(turn);
  r = r * c + w.cross(r) * sin_over_th + w * (w.dot(r) * versine_over_th2);
}

#ifdef DEM_SIMD_LOOPS
// Four ties at a time (simd.hpp: turn_tie's operations in its order, so the same bits); a four
// with a tie whose particle is gone, or an angle beyond the series, goes one by one. Returns the
// first tie not done.
DEM_AVX2 long turn_four_at_a_time(FibreSet& fibres, const Particles& p, double dt) {
  const long ties = static_cast<long>(fibres.ties());
  const Lanes4 step = simd::broadcast(dt), limit = simd::broadcast(kSeriesLimit), zero = simd::broadcast(0.0);
  const int* slot = fibres.tie_slot.data();
  Vec3* offset = fibres.tie_offset.data();
  long t = 0;
  for (; t + 4 <= ties; t += 4) {
    const auto one_by_one = [&] {
      for (long u = t; u < t + 4; ++u) turn_tie(fibres, p, dt, u);
    };
    const int k0 = slot[t], k1 = slot[t + 1], k2 = slot[t + 2], k3 = slot[t + 3];
    if ((k0 | k1 | k2 | k3) < 0) {
      one_by_one();
      continue;
    }
    const Triple<Lanes4> turn = simd::load_four(p.w.data(), k0, k1, k2, k3) * step;
    const Lanes4 th2 = lanes::dot(turn, turn);
    if (simd::bits(simd::not_less_or_equal(th2, limit))) {
      one_by_one();
      continue;
    }
    const int u = static_cast<int>(t);
    const Triple<Lanes4> r = simd::load_four(offset, u, u + 1, u + 2, u + 3);
    Lanes4 out[4];
    simd::per_lane(lanes::select(lanes::equal(th2, zero), r, turned_by_series(r, turn, th2)), out);  // th = 0: as it was
    for (int q = 0; q < 4; ++q) simd::store_xyz(offset[t + q].data(), out[q]);
  }
  return t;
}
#endif

}  // namespace

void rotate_ties(FibreSet& fibres, const Particles& p, double dt) {
  const long ties = static_cast<long>(fibres.ties());
  long t = 0;
#ifdef DEM_SIMD_LOOPS
  if (simd_loops_on()) t = turn_four_at_a_time(fibres, p, dt);
#endif
  for (; t < ties; ++t) turn_tie(fibres, p, dt, t);
}

}  // namespace dem
