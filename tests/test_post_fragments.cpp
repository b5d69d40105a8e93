// Fragments (lib/post/fragments.hpp): the groups of particles joined by intact bonds, checked on
// sets whose groups are known by construction, for any storage and contact order, and at 10^4
// particles (union-find has no size switch, but the sort and the id order are exercised there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "post/fragments.hpp"

namespace dem {
namespace {

constexpr double kRadius = 1e-3, kDensity = 2500;
const double kMass = kDensity * 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;

// Particles with ids 0..n-1 on the x axis, 2 kRadius apart, in storage order `order` (slot k holds
// id order[k]).
Particles row(const std::vector<int>& order) {
  Particles p;
  for (int id : order) p.add(id, Vec3(2 * kRadius * id, 0, 0), kRadius, kDensity, 0);
  return p;
}

int slot_of(const Particles& p, Index id) { return static_cast<int>(std::find(p.id.begin(), p.id.end(), id) - p.id.begin()); }

// Contacts between ids (a, b), bonded or not.
ContactForceSet contacts(const Particles& p, const std::vector<std::array<int, 3>>& list) {
  ContactForceSet c;
  for (const auto& [a, b, bonded] : list) {
    c.pair_i.push_back(slot_of(p, a));
    c.pair_j.push_back(slot_of(p, b));
    c.pair_force.push_back(Vec3::Zero());
    c.pair_normal.push_back(Vec3::UnitX());
    c.pair_bonded.push_back(static_cast<std::uint8_t>(bonded));
  }
  return c;
}

// Ten spheres: bonds 0-1-2-3 (a chain of four), 5-6, 8-9; an unbonded contact 3-4 joins nothing.
// Fragments, largest first and equal masses by smallest id: {0..3}, {5, 6}, {8, 9}, {4}, {7}.
const std::vector<std::array<int, 3>> kTen = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 4, 0}, {5, 6, 1}, {8, 9, 1}};

void expect_ten(const Particles& p, const FragmentSet& f, const char* what) {
  ASSERT_EQ(f.fragments.size(), 5u) << what;
  EXPECT_EQ(f.intact_bonds, 5u) << what;
  const std::size_t sizes[] = {4, 2, 2, 1, 1};
  const Index first[] = {0, 5, 8, 4, 7};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(f.fragments[k].particles, sizes[k]) << what << " fragment " << k;
    EXPECT_EQ(f.fragments[k].first_id, first[k]) << what << " fragment " << k;
    EXPECT_NEAR(f.fragments[k].mass, sizes[k] * kMass, 1e-12 * kMass) << what;
    // Equal spheres: the equivalent diameter is 2 a n^(1/3).
    EXPECT_NEAR(f.fragments[k].equivalent_diameter(), 2 * kRadius * std::cbrt(sizes[k]), 1e-12 * kRadius) << what;
  }
  // The chain's centre of mass: the middle of ids 0..3.
  EXPECT_NEAR(f.fragments[0].centre.x(), 3 * kRadius, 1e-15) << what;
  const int expected_rank[] = {0, 0, 0, 0, 3, 1, 1, 4, 2, 2};  // by id
  for (std::size_t s = 0; s < p.size(); ++s) EXPECT_EQ(f.of_slot[s], expected_rank[p.id[s]]) << what << " id " << p.id[s];
}

TEST(Fragments, GroupsJoinedByIntactBonds) {
  const Particles p = row({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  const FragmentSet f = find_fragments(p, contacts(p, kTen));
  expect_ten(p, f, "in id order");
  // A sieve of aperture d passes the fragments of equivalent diameter <= d: the two singles
  // (2 of 10 masses), then the pairs (6 of 10), then all.
  EXPECT_DOUBLE_EQ(f.mass_passing(2 * kRadius), 0.2);
  EXPECT_DOUBLE_EQ(f.mass_passing(2 * kRadius * std::cbrt(2.0) * (1 + 1e-12)), 0.6);
  EXPECT_DOUBLE_EQ(f.mass_passing(1.0), 1.0);
  EXPECT_DOUBLE_EQ(f.mass_passing(kRadius), 0.0);
}

TEST(Fragments, SameForAnyStorageAndContactOrder) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<int> order = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<std::array<int, 3>> list = kTen;
    std::shuffle(list.begin(), list.end(), rng);
    for (auto& c : list)
      if (rng() % 2) std::swap(c[0], c[1]);
    const Particles p = row(order);
    expect_ten(p, find_fragments(p, contacts(p, list)), "shuffled");
  }
}

// 22^3 = 10,648 spheres on a cubic lattice, bonded along x within each row of 22: 484 fragments
// of 22; then every row cut between x index 6 and 7 as well: 484 of 15 and 484 of 7.
TEST(Fragments, LatticeRowsAtTenThousandParticles) {
  constexpr int n = 22;
  Particles p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.add((k * n + j) * n + i, Vec3(i, j, k) * 2 * kRadius, kRadius, kDensity, 0);
  // Stored in reverse id order: slots and ids differ.
  std::vector<std::size_t> reverse(p.size());
  for (std::size_t s = 0; s < p.size(); ++s) reverse[s] = p.size() - 1 - s;
  p.reorder(reverse);
  for (const int cut : {-1, 6}) {
    std::vector<std::array<int, 3>> list;
    for (int r = 0; r < n * n; ++r)
      for (int i = 0; i + 1 < n; ++i) list.push_back({r * n + i, r * n + i + 1, i != cut});
    ContactForceSet c;
    for (const auto& [a, b, bonded] : list) {
      c.pair_i.push_back(static_cast<int>(p.size()) - 1 - a);
      c.pair_j.push_back(static_cast<int>(p.size()) - 1 - b);
      c.pair_bonded.push_back(static_cast<std::uint8_t>(bonded));
    }
    const FragmentSet f = find_fragments(p, c);
    if (cut < 0) {
      ASSERT_EQ(f.fragments.size(), 484u);
      for (const Fragment& x : f.fragments) EXPECT_EQ(x.particles, 22u);
      EXPECT_EQ(f.fragments[1].first_id, 22) << "equal masses ordered by id";
    } else {
      ASSERT_EQ(f.fragments.size(), 968u);
      for (std::size_t k = 0; k < 968; ++k) EXPECT_EQ(f.fragments[k].particles, k < 484 ? 15u : 7u);
      EXPECT_EQ(f.fragments[0].first_id, 7) << "the larger piece of row 0 starts at x index 7";
      EXPECT_NEAR(f.mass_passing(2 * kRadius * std::cbrt(7.0) * (1 + 1e-12)), 7.0 / 22, 1e-12);
    }
    // Every sphere's fragment holds it: the row's id range.
    for (std::size_t s = 0; s < p.size(); ++s) {
      const Fragment& x = f.fragments[f.of_slot[s]];
      EXPECT_EQ(x.first_id / n, p.id[s] / n);
      ASSERT_LE(x.first_id, p.id[s]);
    }
  }
}

}  // namespace
}  // namespace dem
