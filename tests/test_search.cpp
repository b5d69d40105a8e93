// The linked-cell search must find exactly the overlapping pairs that an O(N^2) check finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "search/linked_cells.hpp"

namespace dem {
namespace {

std::vector<FoundContact> brute_force(const Particles& p) {
  std::vector<FoundContact> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double r = p.radius[i] + p.radius[j];
      if ((p.x[i] - p.x[j]).squaredNorm() < r * r)
        out.push_back({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]), int(i), int(j)});
    }
  std::sort(out.begin(), out.end());
  return out;
}

class SearchMatchesBruteForce : public ::testing::TestWithParam<int> {};

TEST_P(SearchMatchesBruteForce, PolydisperseRandomCloud) {
  std::mt19937_64 rng(GetParam());
  std::uniform_real_distribution<double> u(0, 1);
  Particles p;
  // Size ratio 10 (as in the sand-production case), dense enough for many overlaps; ids shuffled
  // so that id order differs from storage order.
  const int n = 1500;
  std::vector<Index> ids(n);
  for (int k = 0; k < n; ++k) ids[k] = 1000 + 3 * k;
  std::shuffle(ids.begin(), ids.end(), rng);
  for (int k = 0; k < n; ++k) p.add(ids[k], Vec3(u(rng), u(rng), 0.3 * u(rng)), 0.002 + 0.018 * u(rng), 1000, 0);
  // A far-away particle stretches the bounding box (tests the grid-size cap).
  p.add(5, Vec3(50, -20, 3), 0.01, 1000, 0);
  std::vector<FoundContact> fast;
  LinkedCells cells;
  cells.find_overlaps(p, fast);
  for (const FoundContact& c : fast) EXPECT_LT(c.key_i, c.key_j);
  std::sort(fast.begin(), fast.end());
  const std::vector<FoundContact> slow = brute_force(p);
  ASSERT_GT(slow.size(), 100u);
  ASSERT_EQ(fast.size(), slow.size());
  for (std::size_t k = 0; k < fast.size(); ++k) {
    EXPECT_EQ(fast[k].key_i, slow[k].key_i);
    EXPECT_EQ(fast[k].key_j, slow[k].key_j);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SearchMatchesBruteForce, ::testing::Values(1, 2, 3));

}  // namespace
}  // namespace dem
