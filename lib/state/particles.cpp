#include "state/particles.hpp"

#include <algorithm>

#include "core/keep_items.hpp"

namespace dem {

namespace {
template <class T>
void gather(std::vector<T>& a, const std::vector<std::size_t>& order) {
  std::vector<T> b(a.size());
  for (std::size_t k = 0; k < order.size(); ++k) b[k] = a[order[k]];
  a.swap(b);
}
}  // namespace

std::vector<std::size_t> Particles::slots_by_id() const {
  std::vector<std::size_t> order(id.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  return order;
}

void Particles::reorder(const std::vector<std::size_t>& order) {
  gather(id, order);
  gather(x, order);
  gather(v, order);
  gather(w, order);
  gather(x_ref, order);
  gather(image, order);
  gather(radius, order);
  gather(mass, order);
  gather(material, order);
  gather(fixed, order);
  if (void_fraction.size() == order.size()) gather(void_fraction, order);
}

void Particles::keep_only(const Kept& keep) {
  keep_items(id, keep);
  keep_items(x, keep);
  keep_items(v, keep);
  keep_items(w, keep);
  keep_items(x_ref, keep);
  keep_items(image, keep);
  keep_items(radius, keep);
  keep_items(mass, keep);
  keep_items(material, keep);
  keep_items(fixed, keep);
  if (void_fraction.size() == keep.before()) keep_items(void_fraction, keep);
}

Index Particles::max_id() const { return id.empty() ? -1 : *std::max_element(id.begin(), id.end()); }

}  // namespace dem
