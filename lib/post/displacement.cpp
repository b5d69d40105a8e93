#include "post/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace dem {

DisplacementField displacement_by_id(const Particles& ref, const Particles& cur, const PeriodicBox& ref_box, const PeriodicBox& cur_box) {
  std::unordered_map<Index, std::size_t> slot;
  slot.reserve(ref.size());
  for (std::size_t k = 0; k < ref.size(); ++k) slot.emplace(ref.id[k], k);
  DisplacementField d;
  d.u.assign(cur.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t k = 0; k < cur.size(); ++k) {
    auto it = slot.find(cur.id[k]);
    if (it == slot.end()) {
      ++d.added;
      continue;
    }
    d.u[k] = cur_box.unwrapped(cur.x[k], cur.image[k]) - ref_box.unwrapped(ref.x[it->second], ref.image[it->second]);
    ++d.matched;
  }
  d.removed = ref.size() - d.matched;
  return d;
}

std::vector<ProfileRow> displacement_profile(const Particles& cur, const DisplacementField& d, int axis, int bins) {
  std::vector<ProfileRow> rows;
  if (cur.size() == 0 || bins < 1) return rows;
  double lo = cur.x[0][axis], hi = lo;
  for (const Vec3& x : cur.x) lo = std::min(lo, x[axis]), hi = std::max(hi, x[axis]);
  const double width = (hi - lo) / bins;
  rows.resize(bins);
  for (int b = 0; b < bins; ++b) rows[b] = {lo + (b + 0.5) * width, 0, Vec3::Zero(), 0};
  for (std::size_t k = 0; k < cur.size(); ++k) {
    if (!d.u[k].allFinite()) continue;
    const int b = width > 0 ? std::min(bins - 1, static_cast<int>((cur.x[k][axis] - lo) / width)) : 0;
    ++rows[b].count;
    rows[b].mean_u += d.u[k];
    rows[b].mean_norm += d.u[k].norm();
  }
  for (ProfileRow& r : rows)
    if (r.count) r.mean_u /= static_cast<double>(r.count), r.mean_norm /= static_cast<double>(r.count);
  return rows;
}

}  // namespace dem
