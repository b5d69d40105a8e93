#pragma once
// Compacting per-item arrays: the items whose `keep` flag is set, in their order.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace dem {

// Which items stay, as runs of consecutive ones, worked out once from the flags and applied to each
// array of the same items: a removal keeps nearly all, so an array moves in a few block copies
// rather than an item at a time.
class Kept {
 public:
  Kept(const std::vector<bool>& keep) : Kept(keep.size(), [&](std::size_t k) { return keep[k]; }) {}  // NOLINT: flags convert
  // Items 0 .. n-1, item k kept where stays(k).
  template <class Stays>
  Kept(std::size_t n, Stays stays) : before_(n) {
    std::size_t k = 0;
    while (k < n) {
      while (k < n && !stays(k)) ++k;
      const std::size_t from = k;
      while (k < n && stays(k)) ++k;
      if (k > from) runs_.push_back({from, after_, k - from}), after_ += k - from;
    }
  }
  std::size_t before() const { return before_; }  // items before
  std::size_t after() const { return after_; }    // items kept
  // a (before() items) compacted to its kept items, in their order.
  template <class T>
  void apply(std::vector<T>& a) const {
    for (const Run& r : runs_)
      if (r.to != r.from) std::copy(a.begin() + r.from, a.begin() + r.from + r.count, a.begin() + r.to);  // down: no overlap issue
    a.resize(after_);
  }

 private:
  struct Run {
    std::size_t from, to, count;
  };
  std::vector<Run> runs_;
  std::size_t before_ = 0, after_ = 0;
};

template <class T>
void keep_items(std::vector<T>& a, const Kept& keep) {
  keep.apply(a);
}

}  // namespace dem
