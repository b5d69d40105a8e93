#pragma once
// Compacting a per-item array: the items whose `keep` flag is set, in their order.
#include <cstddef>
#include <vector>

namespace dem {

template <class T>
void keep_items(std::vector<T>& a, const std::vector<bool>& keep) {
  std::size_t out = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (keep[k]) a[out++] = a[k];
  a.resize(out);
}

}  // namespace dem
