// The linked-cell search must find exactly the overlapping pairs that an O(N^2) check finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/error.hpp"
#include "core/keep_items.hpp"
#include "generation/fill.hpp"
#include "search/largest_move.hpp"
#include "search/linked_cells.hpp"
#include "sim/simulation.hpp"
#include "simd/simd.hpp"

namespace dem {
namespace {

// Every overlapping pair (closer than the sum of radii + `margin`), between nearest images where
// `box` is periodic; two held particles never interact.
std::vector<FoundContact> brute_force(const Particles& p, const PeriodicBox& box = {}, double margin = 0) {
  std::vector<FoundContact> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double r = p.radius[i] + p.radius[j] + margin;
      if (p.fixed[i] && p.fixed[j]) continue;
      if (box.nearest(p.x[i] - p.x[j]).squaredNorm() < r * r)
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
  for (int k = 0; k < n; k += 7) p.fixed[k] = 1;  // pairs of two held particles are skipped
  // And a dense cloud of equal spheres (several to a search cell: most spheres' neighbours come in
  // groups of four and a remainder).
  Particles dense;
  for (int k = 0; k < n; ++k) dense.add(ids[k], Vec3(0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)), 0.01, 1000, 0);
  // Contacts and candidates (a margin, the skin), by the plain loops and the four-wide ones.
  for (const Particles* cloud : {&p, &dense})
  for (double margin : {0.0, 0.004})
    for (bool simd : {false, simd_loops_available()}) {
      const Particles& p = *cloud;
      SCOPED_TRACE(testing::Message() << (cloud == &dense ? "dense" : "polydisperse") << ", margin " << margin
                                      << (simd ? ", four-wide" : ", plain"));
      set_simd_loops(simd);
      std::vector<FoundContact> fast;
      std::vector<int> groups;
      LinkedCells cells;
      cells.find_near_pairs(p, PeriodicBox{}, fast, groups, margin);
      set_simd_loops(true);
      for (const FoundContact& c : fast) EXPECT_LT(c.key_i, c.key_j);
      // Found grouped by the smaller slot, in key order within a group, as place_by_storage would
      // put them; groups[s] is where slot s's group starts.
      ASSERT_EQ(groups.size(), p.size() + 1);
      EXPECT_EQ(groups.back(), static_cast<int>(fast.size()));
      for (std::size_t s = 0; s < p.size(); ++s)
        for (int k = groups[s]; k < groups[s + 1]; ++k) {
          EXPECT_EQ(std::min(fast[k].slot_i, fast[k].slot_j), static_cast<int>(s));
          if (k > groups[s]) EXPECT_LT(fast[k - 1], fast[k]);
        }
      std::vector<FoundContact> by_key = fast;
      std::sort(by_key.begin(), by_key.end());
      std::vector<int> count;
      KeyOrder place;
      place_by_storage(by_key, p.size(), count, place);
      for (std::size_t r = 0; r < by_key.size(); ++r) {
        EXPECT_EQ(fast[place[r]].key_i, by_key[r].key_i);
        EXPECT_EQ(fast[place[r]].key_j, by_key[r].key_j);
      }
      fast = by_key;
      const std::vector<FoundContact> slow = brute_force(p, PeriodicBox{}, margin);
      ASSERT_GT(slow.size(), 100u);
      ASSERT_EQ(fast.size(), slow.size());
      for (std::size_t k = 0; k < fast.size(); ++k) {
        EXPECT_EQ(fast[k].key_i, slow[k].key_i);
        EXPECT_EQ(fast[k].key_j, slow[k].key_j);
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SearchMatchesBruteForce, ::testing::Values(1, 2, 3));

// Periodic along x and y: the pairs are those between nearest images, with a period of exactly
// three search cells (the fewest the search accepts) and of many, size ratio 10; pairs of two held
// particles are skipped. A period of two cells is refused with a message.
TEST(LinkedCells, PeriodicMatchesBruteForceBetweenNearestImages) {
  std::size_t across = 0;
  for (const auto& [length, n] : {std::pair{0.12, 60}, std::pair{0.5, 1200}}) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    PeriodicBox box;
    box.axis = {true, true, false};
    box.lo = Vec3(0, 0, 0);
    box.hi = Vec3(length, length, 0);
    Particles p;
    for (int k = 0; k < n; ++k) {
      p.add(k, Vec3(length * u(rng), length * u(rng), 0.3 * u(rng)), 0.002 + 0.018 * u(rng), 1000, 0);
      p.fixed[k] = k % 5 == 0;
    }
    p.radius[0] = 0.02;  // 2 Rmax = 0.04 m: a period of 0.12 m is three cells
    std::vector<FoundContact> fast;
    LinkedCells cells;
    cells.find_near_pairs(p, box, fast);
    std::sort(fast.begin(), fast.end());
    const std::vector<FoundContact> slow = brute_force(p, box);
    for (const FoundContact& c : slow) across += (p.x[c.slot_i] - p.x[c.slot_j]).norm() > p.radius[c.slot_i] + p.radius[c.slot_j];
    ASSERT_EQ(fast.size(), slow.size()) << "period " << length;
    for (std::size_t k = 0; k < fast.size(); ++k) {
      EXPECT_EQ(fast[k].key_i, slow[k].key_i);
      EXPECT_EQ(fast[k].key_j, slow[k].key_j);
    }
  }
  EXPECT_GT(across, 3u) << "some pairs touch across the boundary only";
  Particles p;
  p.add(0, Vec3(0.01, 0.01, 0), 0.02, 1000, 0);
  PeriodicBox narrow;
  narrow.axis = {true, false, false};
  narrow.hi = Vec3(0.1, 0, 0);
  std::vector<FoundContact> out;
  try {
    LinkedCells().find_near_pairs(p, narrow, out);
    FAIL() << "a period of two cells must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the period along x (0.1 m) must hold at least 3 search cells"), std::string::npos) << e.what();
  }
}

// A box of side L between a floor and a lid (square quads at z = 0 and z = L), one soft material.
Simulation box_between_plates(double L) {
  Simulation sim;
  Material m;
  m.name = "m";
  m.kn = m.kt = 1e3;
  m.restitution = 0.9;
  sim.materials = MaterialTable({m}, {});
  sim.walls.push_back(Wall{"floor", 0, {Vec3(0, 0, 0), Vec3(L, 0, 0), Vec3(L, L, 0), Vec3(0, L, 0)}, {}});
  sim.walls.push_back(Wall{"lid", 0, {Vec3(0, 0, L), Vec3(L, 0, L), Vec3(L, L, L), Vec3(0, L, L)}, {}});
  return sim;
}

// Along a trajectory (the neighbour list is reused between rebuilds, with a skin), the contacts of
// every step are exactly the overlapping pairs and particle-wall overlaps an O(N^2) check finds,
// with a polydisperse cloud (size ratio 10) moving fast in a box whose lid moves down.
TEST(NeighbourList, ContactsEqualBruteForceEveryStep) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  const double L = 0.05;
  Simulation sim = box_between_plates(L);
  sim.walls[1].motion.velocity = Vec3(0, 0, -0.2);
  for (int k = 0; k < 300; ++k) {
    const double a = 0.0005 + 0.0045 * u(rng);
    sim.particles.add(k, Vec3(a + (L - 2 * a) * u(rng), a + (L - 2 * a) * u(rng), a + (L - 2 * a) * u(rng)), a, 2500, 0);
    sim.particles.v[k] = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  sim.dt = 0.1 * sim.critical_time_step();
  sim.params.max_overlap = 10;  // random placement overlaps deeply; this test is about the search
  std::size_t pair_contacts = 0, wall_contacts = 0;
  for (int s = 0; s < 400; ++s) {
    // The contacts of a step are found at the positions before it: brute force on those.
    const std::vector<FoundContact> pairs = brute_force(sim.particles);
    std::vector<std::pair<Index, Index>> walls;
    for (std::size_t k = 0; k < sim.particles.size(); ++k)
      for (std::size_t w = 0; w < sim.walls.size(); ++w) {
        const std::vector<Vec3> v = sim.walls[w].vertices_at(sim.time);
        const Vec3 c = closest_point_on_polygon(v.data(), 4, Vec3::UnitZ(), sim.particles.x[k]);
        if ((c - sim.particles.x[k]).norm() < sim.particles.radius[k]) walls.emplace_back(sim.particles.id[k], static_cast<Index>(w));
      }
    std::sort(walls.begin(), walls.end());
    sim.advance();
    ASSERT_EQ(sim.pair_contacts().size(), pairs.size()) << "step " << s;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      ASSERT_EQ(sim.pair_contacts().key_i[k], pairs[k].key_i);
      ASSERT_EQ(sim.pair_contacts().key_j[k], pairs[k].key_j);
    }
    ASSERT_EQ(sim.wall_contacts().size(), walls.size()) << "step " << s;
    for (std::size_t k = 0; k < walls.size(); ++k) {
      ASSERT_EQ(sim.wall_contacts().key_i[k], walls[k].first);
      ASSERT_EQ(sim.wall_contacts().key_j[k], walls[k].second);
    }
    pair_contacts += pairs.size();
    wall_contacts += walls.size();
  }
  EXPECT_GT(pair_contacts, 1000u) << "the trajectory must exercise contacts";
  EXPECT_GT(wall_contacts, 100u);
  EXPECT_GT(sim.neighbour_builds(), 3) << "and several list rebuilds";
  EXPECT_LT(sim.neighbour_builds(), 300) << "the list is reused between rebuilds";
}

// Held and released between two rebuilds: pairs of two held particles are no candidates, so the
// list must be rebuilt when the held flags change. Two overlapping spheres held for a step, then
// released (set_fixed, as a stage's release does), repel at the next step: the definition's
// contact is there at once (brute force), and both start to move apart.
TEST(NeighbourList, PairsOfReleasedParticlesAreFoundAtOnce) {
  Simulation sim = box_between_plates(0.1);
  sim.particles.add(1, Vec3(0.05, 0.05, 0.05), 0.005, 2500, 0);
  sim.particles.add(2, Vec3(0.059, 0.05, 0.05), 0.005, 2500, 0);  // overlap 1 mm
  sim.params.gravity = Vec3::Zero();
  sim.dt = 0.1 * sim.critical_time_step();
  EXPECT_EQ(set_fixed(sim, nullptr, true, true), 2u);
  sim.advance();
  EXPECT_EQ(sim.pair_contacts().size(), 0u) << "two held particles never interact";
  const int builds = sim.neighbour_builds();
  EXPECT_EQ(set_fixed(sim, nullptr, true, false), 2u);
  ASSERT_EQ(brute_force(sim.particles).size(), 1u);
  sim.advance();
  EXPECT_EQ(sim.pair_contacts().size(), 1u);
  EXPECT_GT(sim.neighbour_builds(), builds);
  EXPECT_LT(sim.particles.v[0].x(), 0);
  EXPECT_GT(sim.particles.v[1].x(), 0);
  // Held again: the contact ends at the next step.
  EXPECT_EQ(set_fixed(sim, nullptr, true, true), 2u);
  sim.advance();
  EXPECT_EQ(sim.pair_contacts().size(), 0u);
}

// The same along a trajectory in a box periodic along x and y (floor and lid walls in z), with a
// fifth of the particles held in place: every step's pair contacts are those between nearest
// images, particles leave at one side and re-enter at the other (image counts), and a free
// particle's unwrapped position is continuous.
TEST(NeighbourList, PeriodicContactsEqualBruteForceEveryStep) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(0, 1);
  const double L = 0.05;
  Simulation sim = box_between_plates(L);
  PeriodicBox box;
  box.axis = {true, true, false};
  box.hi = Vec3(L, L, 0);
  for (int k = 0; k < 300; ++k) {
    const double a = 0.0005 + 0.0035 * u(rng);
    sim.particles.add(k, Vec3(L * u(rng), L * u(rng), a + (L - 2 * a) * u(rng)), a, 2500, 0);
    sim.particles.v[k] = Vec3(2 * (u(rng) - 0.5), 2 * (u(rng) - 0.5), u(rng) - 0.5);
    sim.particles.fixed[k] = k % 5 == 0;
    if (sim.particles.fixed[k]) sim.particles.v[k] = Vec3::Zero();
  }
  sim.set_periodic(box);
  sim.dt = 0.1 * sim.critical_time_step();
  sim.params.gravity = Vec3::Zero();
  sim.params.max_overlap = 10;  // random placement overlaps deeply; this test is about the search
  std::size_t across = 0, wraps = 0;
  const std::size_t n = sim.particles.size();
  for (int s = 0; s < 400; ++s) {
    const std::vector<FoundContact> pairs = brute_force(sim.particles, box);
    for (const FoundContact& c : pairs)
      across += (sim.particles.x[c.slot_i] - sim.particles.x[c.slot_j]).norm() > sim.particles.radius[c.slot_i] + sim.particles.radius[c.slot_j];
    std::vector<Vec3> before(n);
    std::vector<Vec3i> image = sim.particles.image;
    for (std::size_t k = 0; k < n; ++k) before[k] = sim.unwrapped_position(k);
    sim.advance();
    for (std::size_t k = 0; k < n; ++k) {
      wraps += sim.particles.image[k] != image[k];
      // Unwrapped, every path is continuous: x^{n+1} = x^n + v^{n+1/2} dt (to round-off).
      ASSERT_LT((sim.unwrapped_position(k) - before[k] - sim.particles.v[k] * sim.dt).norm(), 1e-15) << "step " << s << " particle " << k;
    }
    ASSERT_EQ(sim.pair_contacts().size(), pairs.size()) << "step " << s;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      ASSERT_EQ(sim.pair_contacts().key_i[k], pairs[k].key_i);
      ASSERT_EQ(sim.pair_contacts().key_j[k], pairs[k].key_j);
    }
    for (std::size_t k = 0; k < sim.particles.size(); ++k) {
      ASSERT_GE(sim.particles.x[k].x(), 0);
      ASSERT_LT(sim.particles.x[k].x(), L);
      if (sim.particles.fixed[k]) {
        ASSERT_EQ(sim.particles.v[k], Vec3::Zero());
      }
    }
  }
  EXPECT_GT(across, 50u) << "pairs must touch across the boundaries";
  EXPECT_GT(wraps, 10u) << "particles must leave at one side and re-enter at the other";
  EXPECT_GT(sim.neighbour_builds(), 3);
}

// Pair lists are stored along the particles' storage order (place_by_storage), not in key order:
// through a rebuild the history still follows the keys, and active_contacts lists key order.
// The displacements that decide a rebuild: four particles at a time (AVX2) as one by one, and both
// the definitions (d through PeriodicBox::nearest): the largest |d|^2 over the particles and the
// smallest and largest d along each axis, with the largest move placed in each lane of a group of
// four and in the remainder, across a periodic boundary and not, in ranges of every length modulo 4.
TEST(NeighbourList, MovesAreTheDefinitions) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  PeriodicBox box;
  box.axis = {true, false, true};
  box.lo = Vec3(0, 0, -1), box.hi = Vec3(2, 0, 3);
  std::vector<Vec3> before(103), after(103);
  for (std::size_t k = 0; k < before.size(); ++k) {
    before[k] = Vec3(2 * u(rng), 5 * u(rng), -1 + 4 * u(rng));
    after[k] = before[k] + 1e-3 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  for (const PeriodicBox& b : {PeriodicBox(), box})
    for (long big : {0L, 5L, 6L, 7L, 100L, 102L}) {
      std::vector<Vec3> from = before, moved = after;
      // Across the x boundary where periodic: 1.999 -> 0.004 is a move of 0.005 there, 1.995 here.
      moved[big] = from[big] = Vec3(1.999, before[big].y(), before[big].z());
      moved[big].x() = 0.004;
      for (long first : {0L, 1L, 2L, 3L})
        for (long last : {100L, 101L, 102L, 103L}) {
          double expected = 0;
          Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
          for (long k = first; k < last; ++k) {
            const Vec3 d = b.nearest(moved[k] - from[k]);
            expected = std::max(expected, d.squaredNorm());
            lo = lo.cwiseMin(d), hi = hi.cwiseMax(d);
          }
          std::vector<Moves> got;
          for (bool simd : {false, simd_loops_available()}) {
            set_simd_loops(simd);
            got.push_back(moves_since(moved.data(), from.data(), b, first, last));
          }
          set_simd_loops(true);
          for (const Moves& g : got) {
            EXPECT_EQ(g.largest2, expected) << "largest at " << big << ", particles " << first << " to " << last;
            for (int axis = 0; axis < 3; ++axis) {
              EXPECT_EQ(g.lo[axis], lo[axis]);
              EXPECT_EQ(g.hi[axis], hi[axis]);
            }
          }
          if (big >= first && big < last) EXPECT_NEAR(std::sqrt(expected), b.any() ? 0.005 : 1.995, 1e-3);
        }
    }
}

// Moves::approach() bounds how much closer any two particles came (docs/physics.md eq. P85), by
// all pairs: displacements in every direction, a common drift with a little scatter, one particle
// alone moving, all the same, none. It is never more than twice the largest move (the criterion
// before it), and far less where the particles move together.
TEST(NeighbourList, ApproachBoundsEveryPairsApproach) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 drift(3e-4, -2e-4, 5e-4);
  enum Kind { kEveryWay, kTogether, kOneAlone, kAllTheSame, kNone };
  const char* const names[] = {"every way", "together with scatter", "one alone", "all the same", "none"};
  for (int kind = kEveryWay; kind <= kNone; ++kind) {
    std::vector<Vec3> from(57), to(57);
    for (std::size_t k = 0; k < from.size(); ++k) {
      from[k] = Vec3(u(rng), u(rng), u(rng));
      const Vec3 scatter(u(rng), u(rng), u(rng));
      Vec3 d = Vec3::Zero();
      switch (kind) {
        case kEveryWay: d = 1e-4 * scatter; break;
        case kTogether: d = drift + 1e-6 * scatter; break;
        case kOneAlone: d = k == 9 ? drift : Vec3::Zero(); break;
        case kAllTheSame: d = drift; break;
      }
      to[k] = from[k] + d;
    }
    SCOPED_TRACE(names[kind]);
    for (bool simd : {false, simd_loops_available()}) {
      set_simd_loops(simd);
      const Moves m = moves_since(to.data(), from.data(), PeriodicBox(), 0, static_cast<long>(to.size()));
      double closer = 0;  // the most any pair came closer: |d_a - d_b|
      for (std::size_t a = 0; a < to.size(); ++a)
        for (std::size_t b = a + 1; b < to.size(); ++b) closer = std::max(closer, ((to[a] - from[a]) - (to[b] - from[b])).norm());
      EXPECT_GE(m.approach(), closer * (1 - 1e-12));
      EXPECT_LE(m.approach(), 2 * std::sqrt(m.largest2));
      if (kind == kTogether) EXPECT_LT(m.approach(), 0.01 * 2 * std::sqrt(m.largest2));
      if (kind == kAllTheSame) EXPECT_LT(m.approach(), 1e-15) << "only the positions' round-off";
      if (kind == kNone) EXPECT_EQ(m.approach(), 0.0);
    }
    set_simd_loops(true);
  }
  EXPECT_EQ(Moves().approach(), 0.0) << "no particles";
}

// A cloud moving together, far from any wall, keeps its list however far it goes: its particles
// come no closer to each other (eq. P85), though each moves a hundred skins, falling in open space
// or drifting across the periods of a periodic box (displacements through the nearest image). Two
// of them aimed at each other then make it rebuild in time: every step's contacts are the
// definition's.
TEST(NeighbourList, ACloudMovingTogetherKeepsItsList) {
  for (bool periodic : {false, true}) {
    SCOPED_TRACE(periodic ? "drifting across periodic boundaries" : "falling in open space");
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> u(0, 1);
    Simulation sim = box_between_plates(0.1);
    sim.walls.clear();
    sim.params.skin = 1e-4;
    for (int k = 0; k < 125; ++k)  // a 5 x 5 x 5 lattice, 2 mm spheres 1 cm apart, each nudged
      sim.particles.add(k, Vec3(0.01 * (k % 5) + 0.002 * u(rng), 0.01 * (k / 5 % 5) + 0.002 * u(rng), 0.01 * (k / 25) + 0.002 * u(rng)),
                        0.002, 2500, 0);
    PeriodicBox box;
    Vec3 v(0.5, -0.2, 1.0);
    sim.params.gravity = Vec3(0, 0, -9.81);
    if (periodic) {  // periods of 5 cm along x and y: the lattice fills them
      box.axis = {true, true, false};
      box.hi = Vec3(0.05, 0.05, 0);
      sim.set_periodic(box);
      v.z() = 0, sim.params.gravity = Vec3::Zero();
    }
    for (std::size_t k = 0; k < sim.particles.size(); ++k) sim.particles.v[k] = v;
    sim.dt = 1e-5;
    std::size_t wrapped = 0;
    for (int s = 0; s < 2000; ++s) {
      sim.advance();
      if (s == 1999)
        for (std::size_t k = 0; k < sim.particles.size(); ++k) wrapped += sim.particles.image[k] != Vec3i::Zero();
    }
    const double moved = 0.02 * Vec3(v.x(), v.y(), v.z() + 0.5 * sim.params.gravity.z() * 0.02).norm();  // 2,000 steps of 1e-5 s
    EXPECT_GT(moved, 100 * sim.params.skin);
    if (periodic) EXPECT_GT(wrapped, 10u) << "particles must have crossed a boundary";
    EXPECT_EQ(sim.neighbour_builds(), 1) << "the first build only";
    // Two neighbours sent towards each other at 1 m/s: 4 to 8 mm apart, they touch within 1,000 steps.
    sim.particles.v[0] += Vec3(0.5, 0, 0), sim.particles.v[1] -= Vec3(0.5, 0, 0);
    std::size_t touching = 0;
    for (int s = 0; s < 1000; ++s) {
      const std::vector<FoundContact> pairs = brute_force(sim.particles, box);
      sim.advance();
      ASSERT_EQ(sim.pair_contacts().size(), pairs.size()) << "step " << s;
      touching += pairs.size();
    }
    EXPECT_GT(touching, 0u) << "the two must have met";
    EXPECT_GT(sim.neighbour_builds(), 1);
  }
}

TEST(ContactList, HistoryFollowsKeysWhereverStored) {
  // Ids 1, 2, 3, 5 in slots 4, 3, 2, 0: three candidates, in key order.
  const std::vector<FoundContact> first = {{1, 2, 4, 3}, {1, 5, 4, 0}, {2, 3, 3, 2}};
  std::vector<int> count;
  KeyOrder place, by_key;
  place_by_storage(first, 5, count, place);
  // Grouped by the smaller slot: (1,5) at slot 0, (2,3) at 2, (1,2) at 3.
  EXPECT_EQ(place, (KeyOrder{2, 0, 1}));
  ContactList list;
  std::vector<int> from;
  carry_history(list, by_key, first, place, from);
  ASSERT_EQ(by_key, (KeyOrder{2, 0, 1}));
  EXPECT_EQ(list.key_j, (std::vector<Index>{5, 3, 2}));
  for (std::size_t k = 0; k < list.size(); ++k) list.spring[k] = Vec3(list.key_j[k], 0, 0), list.active[k] = 1;
  list.bonded[0] = 1;  // (1,5)
  // Rebuild: (1,2) is gone, (1,3) is new.
  const std::vector<FoundContact> second = {{1, 3, 4, 2}, {1, 5, 4, 0}, {2, 3, 3, 2}};
  place_by_storage(second, 5, count, place);
  EXPECT_EQ(place, (KeyOrder{1, 0, 2}));  // slot 0: (1,5); slot 2: (1,3) then (2,3), in key order
  carry_history(list, by_key, second, place, from);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list.spring[0], Vec3(5, 0, 0));  // (1,5) kept its spring and bond
  EXPECT_EQ(list.bonded[0], 1);
  EXPECT_EQ(list.spring[1], Vec3::Zero());   // (1,3) is new: no history
  EXPECT_EQ(list.active[1], 0);
  EXPECT_EQ(list.spring[2], Vec3(3, 0, 0));  // (2,3)
  EXPECT_EQ(list.bonded[2], 0);
  ContactList view;
  active_contacts(list, by_key, view);  // the contacts of the last step, in key order
  EXPECT_EQ(view.key_i, (std::vector<Index>{1, 2}));
  EXPECT_EQ(view.key_j, (std::vector<Index>{5, 3}));
  KeyOrder sorted;
  sort_by_key(list, sorted);
  EXPECT_EQ(sorted, by_key);

  // The same rebuild carried group by group (no sort), from the list as the first build left it:
  // the search gives the candidates grouped by the smaller slot (slot 0: (1,5); slot 2: (1,3),
  // (2,3)), and the slots still hold the same ids (slot 1 holds a particle without candidates).
  ContactList grouped;
  KeyOrder grouped_by_key;
  place_by_storage(first, 5, count, place);
  carry_history(grouped, grouped_by_key, first, place, from);
  for (std::size_t k = 0; k < grouped.size(); ++k) grouped.spring[k] = Vec3(grouped.key_j[k], 0, 0), grouped.active[k] = 1;
  grouped.bonded[0] = 1;
  const std::vector<FoundContact> second_grouped = {{1, 5, 4, 0}, {1, 3, 4, 2}, {2, 3, 3, 2}};
  const std::vector<int> groups = {0, 1, 1, 3, 3, 3};
  const std::vector<Index> id_of_slot = {5, 9, 3, 2, 1};
  // Slots that no longer hold their keys' particles (re-sorted storage) are refused, untouched.
  const ContactList before = grouped;
  EXPECT_FALSE(carry_history_in_groups(grouped, second_grouped, groups, {5, 9, 3, 1, 2}, from));
  EXPECT_EQ(grouped.key_j, before.key_j);
  EXPECT_EQ(grouped.spring, before.spring);
  ASSERT_TRUE(carry_history_in_groups(grouped, second_grouped, groups, id_of_slot, from));
  EXPECT_EQ(grouped.key_i, list.key_i);
  EXPECT_EQ(grouped.key_j, list.key_j);
  EXPECT_EQ(grouped.slot_i, list.slot_i);
  EXPECT_EQ(grouped.slot_j, list.slot_j);
  EXPECT_EQ(grouped.spring, list.spring);
  EXPECT_EQ(grouped.bonded, list.bonded);
  EXPECT_EQ(grouped.active, list.active);
  // And again from a list stored grouped: the carry needs no key order.
  for (std::size_t k = 0; k < grouped.size(); ++k) grouped.spring[k] = Vec3(0, grouped.key_i[k], grouped.key_j[k]);
  ASSERT_TRUE(carry_history_in_groups(grouped, second_grouped, groups, id_of_slot, from));
  EXPECT_EQ(grouped.spring, (std::vector<Vec3>{Vec3(0, 1, 5), Vec3(0, 1, 3), Vec3(0, 2, 3)}));
}

// Kept (core/keep_items.hpp) compacts an array by runs of kept items: the same items in the same
// order as taking them one at a time, wherever the removed ones lie (first, last, in runs, none, all).
TEST(Kept, CompactsAsTakingTheKeptItemsOneByOne) {
  std::mt19937_64 rng(5);
  for (const std::vector<bool>& keep :
       {std::vector<bool>{}, {true, true, true}, {false, false}, {false, true, true, false, true, false, false, true}, {true, false}}) {
    std::vector<int> a(keep.size()), want;
    for (std::size_t k = 0; k < a.size(); ++k) a[k] = static_cast<int>(10 + k);
    for (std::size_t k = 0; k < a.size(); ++k)
      if (keep[k]) want.push_back(a[k]);
    const Kept kept(keep);
    kept.apply(a);
    EXPECT_EQ(a, want);
    EXPECT_EQ(kept.before(), keep.size());
    EXPECT_EQ(kept.after(), want.size());
  }
  std::vector<bool> keep(10000);  // a few removed among many: long runs, each moved down at once
  for (std::size_t k = 0; k < keep.size(); ++k) keep[k] = rng() % 500 != 0;
  std::vector<Vec3> a(keep.size()), want;
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = Vec3(k, 2 * k, 3 * k);
  for (std::size_t k = 0; k < a.size(); ++k)
    if (keep[k]) want.push_back(a[k]);
  ASSERT_LT(want.size(), a.size());
  keep_items(a, Kept(keep));
  EXPECT_EQ(a, want);
}

}  // namespace
}  // namespace dem
