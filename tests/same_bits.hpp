#pragma once
// Whether two arrays hold the same bits: the determinism and SIMD tests compare runs so.
#include <cstring>
#include <vector>

namespace dem {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  // memcmp must not see the null data() of empty vectors (UBSan), even for a length of 0.
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace dem
