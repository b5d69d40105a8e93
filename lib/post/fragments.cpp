#include "post/fragments.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace dem {

namespace {

// Union-find over storage slots, with path halving; the root of a set is its smallest slot, so the
// sets (not their roots' history) decide the result.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  }
  void join(int a, int b) {
    a = root(a), b = root(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

double Fragment::equivalent_diameter() const { return std::cbrt(6 * volume / std::numbers::pi); }

double FragmentSet::mass_passing(double d) const {
  double total = 0, passing = 0;
  for (const Fragment& f : fragments) {
    total += f.mass;
    if (f.equivalent_diameter() <= d) passing += f.mass;
  }
  return total > 0 ? passing / total : 0;
}

FragmentSet find_fragments(const Particles& p, const ContactForceSet& contacts) {
  FragmentSet out;
  const std::size_t n = p.size();
  DisjointSets sets(n);
  for (std::size_t k = 0; k < contacts.pairs(); ++k)
    if (contacts.pair_bonded[k]) {
      sets.join(contacts.pair_i[k], contacts.pair_j[k]);
      ++out.intact_bonds;
    }
  // Sums in the order of the particles' ids: the same bits for any storage order.
  std::vector<int> of_root(n, -1);
  std::vector<Vec3> moment;
  for (std::size_t s : p.slots_by_id()) {
    const int r = sets.root(static_cast<int>(s));
    if (of_root[r] < 0) {
      of_root[r] = static_cast<int>(out.fragments.size());
      out.fragments.emplace_back();
      out.fragments.back().first_id = p.id[s];
      moment.push_back(Vec3::Zero());
    }
    Fragment& f = out.fragments[of_root[r]];
    ++f.particles;
    f.mass += p.mass[s];
    f.volume += 4.0 / 3.0 * std::numbers::pi * p.radius[s] * p.radius[s] * p.radius[s];
    moment[of_root[r]] += p.mass[s] * p.x[s];
  }
  for (std::size_t f = 0; f < out.fragments.size(); ++f) out.fragments[f].centre = moment[f] / out.fragments[f].mass;
  // Largest first; the index each fragment moves to, for of_slot.
  std::vector<int> order(out.fragments.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Fragment &x = out.fragments[a], &y = out.fragments[b];
    return x.mass != y.mass ? x.mass > y.mass : x.first_id < y.first_id;
  });
  std::vector<int> rank(order.size());
  std::vector<Fragment> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<int>(k), sorted[k] = out.fragments[order[k]];
  out.fragments.swap(sorted);
  out.of_slot.resize(n);
  for (std::size_t s = 0; s < n; ++s) out.of_slot[s] = rank[of_root[sets.root(static_cast<int>(s))]];
  return out;
}

}  // namespace dem
