// The same inputs give the same bits for any thread count (forces are summed per particle in a
// fixed order, DESIGN.md).
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <type_traits>

#include "generation/fill.hpp"
#include "sim/energy_audit.hpp"
#include "io/checkpoint.hpp"
#include "post/contact_forces.hpp"
#include "core/block_times.hpp"
#include "forces/force_loop.hpp"
#include "simd/simd.hpp"
#include "contact/model_table.hpp"
#include "sim/simulation.hpp"

#include "bead_cloud.hpp"
#include "glass.hpp"
#include "same_bits.hpp"

namespace dem {
namespace {

// Glass beads with friction: the material of both scenes below.
MaterialTable glass() { return glass_beads(25); }

Simulation make_cloud() {
  Simulation sim = bead_cloud();
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

// The particles stored in a random order (as random placement leaves them).
void shuffle_storage(Simulation& s, unsigned seed) {
  std::vector<std::size_t> order(s.particles.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  s.particles.reorder(order);
}

// Also with small load blocks (SimParams::load_block), so that the threads share out many blocks,
// and with the storage re-sorted every 7 steps; three threads too (an odd count, more threads than
// this machine's cores), and a run whose thread count changes from step to step (the shares of
// the last step no longer fit).
TEST(Determinism, OneTwoAndThreeThreadsGiveTheSameBits) {
  const int threads_before = omp_get_max_threads();
  for (const long block : {16L, 256L}) {
    auto make = [&] {
      Simulation s = make_cloud();
      s.params.load_block = block;
      s.params.sort_every = 7, s.params.sort_min_particles = 0;
      return s;
    };
    Simulation a = make();
    omp_set_num_threads(1);
    for (int s = 0; s < 1500; ++s) a.advance();
    ASSERT_GT(a.pair_contacts().size(), 0u) << "the test must exercise contacts";
    for (int threads : {2, 3, 0}) {  // 0: 1, 2 and 3 threads in turn
      Simulation b = make();
      omp_set_num_threads(threads ? threads : 1);
      for (int s = 0; s < 1500; ++s) {
        if (threads == 0) omp_set_num_threads(1 + s % 3);
        b.advance();
      }
      const std::string what = "load_block " + std::to_string(block) + ", " +
                               (threads ? std::to_string(threads) : std::string("1-2-3")) + " threads";
      EXPECT_TRUE(same_bits(a.particles.x, b.particles.x)) << what;
      EXPECT_TRUE(same_bits(a.particles.v, b.particles.v)) << what;
      EXPECT_TRUE(same_bits(a.particles.w, b.particles.w)) << what;
      EXPECT_TRUE(same_bits(a.pair_contacts().spring, b.pair_contacts().spring)) << what;
    }
  }
  omp_set_num_threads(threads_before);
}

// Spheres of diameter 1 mm on a 10 x 10 x 10 lattice of spacing 0.99 mm, periodic along every
// axis, with random velocities: each presses against its six neighbours, which lie in several load
// blocks, so each particle's loads sum six contacts and any other order of the sums changes bits
// (unlike the sparse cloud, where few particles have three contacts at once). With x_walls, two
// walls at x = 0 and x = 10 spacings press the first and last sphere of every row (storage is
// sorted along z, then y, then x: such spheres lie in every block) in place of the period along x.
Simulation make_pressed_lattice(bool x_walls = false, double radius_spread = 0) {
  Simulation sim;
  sim.materials = glass();
  sim.params.gravity = Vec3::Zero();
  constexpr int kSide = 10;
  constexpr double kSpacing = 0.99e-3;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  Index id = 0;
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        sim.particles.add(id, kSpacing * Vec3(i + 0.5, j + 0.5, k + 0.5), 0.5e-3 * (1 + radius_spread * ((i + j + k) % 5)), 1, 0);
        sim.particles.v[id++] = Vec3(u(rng), u(rng), u(rng));
      }
  PeriodicBox box;
  box.axis = {!x_walls, true, true};
  box.hi = Vec3::Constant(kSpacing * kSide);
  sim.set_periodic(box);
  if (x_walls)
    for (bool side : {false, true}) sim.walls.push_back(Wall{"w", 0, box_face(Vec3::Zero(), box.hi, 0, side), {}});
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

// A removal after a step (the sink, the `remove` action: generation/fill.hpp remove_marked)
// filters the candidate lists and keeps the neighbour list (Simulation::remove_from_lists), so no
// search follows; the run keeps the bits of one that searches again after each removal, its
// history carried over by id keys (the lists first replaced by the contacts, as a checkpoint's
// are). The pressed lattice with walls, half its contacts bonded, two threads, its storage
// re-sorted every 10 steps; five particles removed every 8 steps, six times. Twice: with the
// scene's skin, and with the automatic one (0.2 x the mean radius, which the removals change: the
// list keeps the skin it was built with) on radii of five sizes.
class DeterminismRemoval : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(Skin, DeterminismRemoval, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Automatic" : "Scene"; });
TEST_P(DeterminismRemoval, ARemovalFiltersTheListsWithTheBitsOfANewSearch) {
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(2);
  const bool automatic = GetParam();
  const auto scene = [automatic] {
    Simulation s = make_pressed_lattice(true, automatic ? 0.002 : 0.0);
    s.params.sort_min_particles = 0, s.params.sort_every = 10;
    s.params.skin = automatic ? 0.0 : 0.3e-3;  // either: no rebuild from the particles' own motion within these steps
    s.advance();
    s.bond_present_contacts(true);
    return s;
  };
  Simulation filtered = scene(), searched = scene();
  ASSERT_GT(filtered.bonds(), 1000);
  std::mt19937_64 rng(3);
  std::size_t removed = 0;
  for (int round = 0; round < 6; ++round) {
    for (int k = 0; k < 7; ++k) filtered.advance(), searched.advance();
    std::vector<char> gone(filtered.particles.size(), 0);
    for (int r = 0; r < 5; ++r) gone[rng() % gone.size()] = 1;
    searched.set_contacts(searched.pair_contacts(), searched.wall_contacts());
    const std::int64_t builds = filtered.neighbour_builds();
    const std::size_t n = remove_marked(filtered, gone);
    ASSERT_EQ(remove_marked(searched, gone), n);
    removed += n;
    const bool sorts = filtered.step % 10 == 0;  // this step re-sorts the storage, and so searches
    filtered.advance(), searched.advance();
    if (!sorts) EXPECT_EQ(filtered.neighbour_builds(), builds) << "a search after the removal, round " << round;
    ASSERT_EQ(filtered.particles.size(), searched.particles.size());
    EXPECT_TRUE(same_bits(filtered.particles.id, searched.particles.id)) << "round " << round;
    EXPECT_TRUE(same_bits(filtered.particles.x, searched.particles.x)) << "round " << round;
    EXPECT_TRUE(same_bits(filtered.particles.v, searched.particles.v)) << "round " << round;
    EXPECT_TRUE(same_bits(filtered.particles.w, searched.particles.w)) << "round " << round;
  }
  EXPECT_GE(removed, 25u);
  EXPECT_EQ(filtered.bonds(), searched.bonds());
  EXPECT_TRUE(same_bits(filtered.pair_contacts().key_i, searched.pair_contacts().key_i));
  EXPECT_TRUE(same_bits(filtered.pair_contacts().spring, searched.pair_contacts().spring));
  EXPECT_TRUE(same_bits(filtered.wall_contacts().spring, searched.wall_contacts().spring));
  omp_set_num_threads(threads_before);
}

// SimParams::parallel_min_particles: a step of fewer particles runs on one thread, a larger one on
// all, and the caller's thread count is back after the step; the bits are those of two threads
// throughout (the pressed lattice: 1,000 spheres, every sum of six contacts).
TEST(Determinism, SmallScenesStepOnOneThreadWithTheSameBits) {
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(2);
  Simulation all = make_pressed_lattice(true), cut = make_pressed_lattice(true);
  cut.params.parallel_min_particles = 1001;  // one more than the lattice: below the cut-off
  for (int s = 0; s < 60; ++s) {
    all.advance(), cut.advance();
    ASSERT_EQ(all.step_threads(), 2);
    ASSERT_EQ(cut.step_threads(), 1);
    ASSERT_EQ(omp_get_max_threads(), 2) << "the thread count before the step is restored";
  }
  ASSERT_GT(all.pair_contact_count(), 500u) << "the test must exercise contacts";
  EXPECT_TRUE(same_bits(all.particles.x, cut.particles.x));
  EXPECT_TRUE(same_bits(all.particles.v, cut.particles.v));
  EXPECT_TRUE(same_bits(all.particles.w, cut.particles.w));
  cut.params.parallel_min_particles = 1000;  // the lattice's size: at the cut-off, all threads
  cut.advance();
  EXPECT_EQ(cut.step_threads(), 2);
  omp_set_num_threads(threads_before);
}

// Each particle's contact forces are added in the order of its contacts' keys (particle ids), so
// neither the storage order nor the thread count changes a bit. The pressed lattice, stored as
// built (never sorted), shuffled (never sorted), and shuffled and sorted along the cells every 7
// steps, on one, two and three threads, with blocks of 16 slots and of 256, ends with the same
// bits particle by particle (matched by id), with periodic axes and with walls (and each wall's
// load the same bits). The scene can tell: each sphere's six contact forces summed in another
// order give other bits for some sphere.
TEST(Determinism, StorageOrderAndThreadsChangeNoBit) {
  const int threads_before = omp_get_max_threads();
  constexpr int kSteps = 60;
  auto by_id = [](const Simulation& s, const std::vector<Vec3>& field) {
    std::vector<Vec3> out(field.size());
    for (std::size_t k = 0; k < field.size(); ++k) out[s.particles.id[k]] = field[k];
    return out;
  };
  for (bool walls : {false, true}) {
    auto run = [&](bool shuffled, long sort_every, long block, int threads) {
      Simulation s = make_pressed_lattice(walls);
      if (shuffled) shuffle_storage(s, 5);
      s.params.sort_every = sort_every, s.params.sort_min_particles = 0;
      s.params.load_block = block;
      omp_set_num_threads(threads);
      for (int k = 0; k < kSteps; ++k) s.advance();
      return s;
    };
    const Simulation one = run(false, 0, 256, 1);
    ASSERT_EQ(one.pair_contacts().size(), walls ? 2900u : 3000u) << "every sphere must touch its six neighbours";
    if (walls) ASSERT_EQ(one.wall_contacts().size(), 200u) << "the walls must touch the ends of every row";
    {  // another order of the sums changes bits: the force on each sphere summed backwards
      const ContactList& c = one.pair_contacts();
      std::vector<Vec3> forward(one.particles.size(), Vec3::Zero()), backward = forward;
      for (std::size_t k = 0; k < c.size(); ++k) forward[c.slot_i[k]] += c.force(k), forward[c.slot_j[k]] -= c.force(k);
      for (std::size_t k = c.size(); k-- > 0;) backward[c.slot_i[k]] += c.force(k), backward[c.slot_j[k]] -= c.force(k);
      ASSERT_FALSE(same_bits(forward, backward)) << "another order of the sums must change bits for the test to mean anything";
    }
    for (const bool shuffled : {false, true})
      for (const long sort_every : {0L, 7L})
        for (const long block : {16L, 256L})
          for (const int threads : {1, 2, 3}) {
            if (!shuffled && sort_every == 0 && block == 256 && threads == 1) continue;  // `one`
            const Simulation s = run(shuffled, sort_every, block, threads);
            const std::string what = std::string(walls ? "walls, " : "") + (shuffled ? "shuffled, " : "") + "sorted every " +
                                     std::to_string(sort_every) + ", blocks of " + std::to_string(block) + ", " +
                                     std::to_string(threads) + " threads";
            if (shuffled) ASSERT_NE(s.particles.id, one.particles.id) << what << ": the storage orders must differ";
            EXPECT_TRUE(same_bits(by_id(one, one.particles.x), by_id(s, s.particles.x))) << what;
            EXPECT_TRUE(same_bits(by_id(one, one.particles.v), by_id(s, s.particles.v))) << what;
            EXPECT_TRUE(same_bits(by_id(one, one.particles.w), by_id(s, s.particles.w))) << what;
            EXPECT_TRUE(same_bits(one.pair_contacts().spring, s.pair_contacts().spring)) << what;
            if (walls) {  // each wall's load (the wall log, a servo) summed in key order: wall candidates are stored by slot
              std::vector<Vec3> f_one, f_s;
              for (const WallLoad& l : one.wall_loads(false)) f_one.push_back(l.force);
              for (const WallLoad& l : s.wall_loads(false)) f_s.push_back(l.force);
              EXPECT_TRUE(same_bits(f_one, f_s)) << what;
            }
          }
  }
  omp_set_num_threads(threads_before);
}

// The same with Hertz-Mindlin and rolling resistance (each contact's couple joins its torque in
// key order): the pressed lattice with walls, shuffled and sorted, on one to three threads, and
// with the plain loops in place of the four-wide sums, ends with the one-thread bits, the rolling
// history included; and the couples do act (the spins differ from a run without rolling
// resistance).
TEST(Determinism, RollingResistanceChangesNoBitWithStorageOrThreads) {
  const int threads_before = omp_get_max_threads();
  auto by_id = [](const Simulation& s, const std::vector<Vec3>& field) {
    std::vector<Vec3> out(field.size());
    for (std::size_t k = 0; k < field.size(); ++k) out[s.particles.id[k]] = field[k];
    return out;
  };
  for (const RollingLaw rolling : {RollingLaw::ConstantTorque, RollingLaw::ElasticPlastic}) {
    auto run = [&](RollingLaw law, bool shuffled, int threads, bool four_wide = true) {
      Simulation s = make_pressed_lattice(true);
      Material m = glass().materials()[0];
      m.law = NormalLaw::Hertz, m.tangential = TangentialLaw::Mindlin, m.rolling = law;
      m.young_modulus = 1e7, m.poisson_ratio = 0.3, m.rolling_friction = 0.2;
      s.materials = MaterialTable({m}, {});
      s.dt = 0.1 * s.critical_time_step();
      if (shuffled) shuffle_storage(s, 5);
      s.params.sort_every = shuffled ? 7 : 0, s.params.sort_min_particles = 0;
      s.params.load_block = 16;
      omp_set_num_threads(threads);
      set_simd_loops(four_wide && simd_loops_available());
      for (int k = 0; k < 60; ++k) s.advance();
      set_simd_loops(simd_loops_available());
      return s;
    };
    const Simulation one = run(rolling, false, 1);
    const Simulation plain = run(rolling, false, 1, false);
    EXPECT_TRUE(same_bits(one.particles.w, plain.particles.w)) << "plain loops";
    const Simulation without = run(RollingLaw::None, false, 1);
    ASSERT_FALSE(same_bits(one.particles.w, without.particles.w)) << "the couples must act for the test to mean anything";
    for (const bool shuffled : {false, true})
      for (const int threads : {1, 2, 3}) {
        if (!shuffled && threads == 1) continue;
        const Simulation s = run(rolling, shuffled, threads);
        const std::string what = std::string(rolling_law_name(rolling)) + (shuffled ? ", shuffled" : "") + ", " +
                                 std::to_string(threads) + " threads";
        EXPECT_TRUE(same_bits(by_id(one, one.particles.x), by_id(s, s.particles.x))) << what;
        EXPECT_TRUE(same_bits(by_id(one, one.particles.w), by_id(s, s.particles.w))) << what;
        EXPECT_TRUE(same_bits(one.pair_contacts().rolling, s.pair_contacts().rolling)) << what;
      }
  }
  omp_set_num_threads(threads_before);
}

// The threads' runs of blocks are cut from the blocks' times smoothed over the last steps: the
// estimates until the first timed step, then that step's times, then each step a quarter of the
// way to the latest (integer ticks), so that one slow block in one step moves a cut by a quarter
// of what it would alone. Hand-worked values.
TEST(BlockTimes, RunsAreCutFromSmoothedTimes) {
  BlockTimes t;
  t.fit(4, [](long) { return 1L; });  // estimates: four equal blocks
  EXPECT_EQ(t.run_start(1, 2), 2);
  t.ticks = {100, 100, 100, 100};
  t.fit(4, [](long) { return 1L; });  // the first timed step replaces the estimates
  EXPECT_EQ(t.fitted, (std::vector<long>{100, 100, 100, 100}));
  t.ticks = {100, 100, 100, 500};  // one step where the last block was slow
  t.fit(4, [](long) { return 1L; });
  EXPECT_EQ(t.fitted, (std::vector<long>{100, 100, 100, 200}));
  EXPECT_EQ(t.total, 500);
  EXPECT_EQ(t.run_start(1, 2), 2) << "the cut stays after the second block (the third's middle, 250, is not below half of 500); "
                                      "from the step's times alone ({100, 100, 100, 500}) it would move past the third";
  t.ticks = {100, 100, 100, 100};
  t.fit(4, [](long) { return 1L; });
  EXPECT_EQ(t.fitted[3], 175);
  t.fit(5, [](long) { return 7L; });  // a new count of blocks: estimates again
  EXPECT_EQ(t.fitted, (std::vector<long>{7, 7, 7, 7, 7}));
}

// A particle is summed only once every contact it needs is computed, whatever the threads' pace:
// one thread of two or three pauses before each block it computes (set_lagging_thread_for_tests),
// so that the others reach the particles whose contacts lie in its blocks first and would sum them
// too early were a wait missing. The pressed lattice in blocks of 16 slots (the runs' first blocks
// hold contacts of the run before), periodic and with walls: the one-thread bits every time.
TEST(Determinism, SumsWaitForTheirContactsWhenAThreadLags) {
  const int threads_before = omp_get_max_threads();
  for (const bool walls : {false, true}) {
    auto run = [&](int threads, int lagging) {
      Simulation s = make_pressed_lattice(walls);
      s.params.load_block = 16;
      omp_set_num_threads(threads);
      set_lagging_thread_for_tests(lagging, 50);
      for (int k = 0; k < 30; ++k) s.advance();
      set_lagging_thread_for_tests(-1, 0);
      return s;
    };
    const Simulation one = run(1, -1);
    for (const int threads : {2, 3})
      for (int lagging = 0; lagging < threads; ++lagging) {
        const Simulation s = run(threads, lagging);
        const std::string what = std::string(walls ? "walls, " : "") + std::to_string(threads) + " threads, thread " +
                                 std::to_string(lagging) + " lagging";
        EXPECT_TRUE(same_bits(one.particles.x, s.particles.x)) << what;
        EXPECT_TRUE(same_bits(one.particles.v, s.particles.v)) << what;
        EXPECT_TRUE(same_bits(one.particles.w, s.particles.w)) << what;
      }
  }
  omp_set_num_threads(threads_before);
}

// Where nothing reads the state between the loads and the motion, each block of particles moves
// within the force loop as soon as its loads are summed (ForceBlocks::motion), its state kept for
// the energy ledger as it moves, and on the energy check's measuring steps its energy taken before
// it moves (ForceBlocks::energy_before_motion); the check's reference step (or, here, every step:
// set_motion_apart_for_tests) takes them apart. Both end with the same bits, the ledger's figures
// and the energy check's balance included (its energies summed in the loop, at steps 10, 20 and
// 30, against the separate pass's): on one thread, and on three with small blocks and each
// thread in turn lagging (a block moved before another thread's contacts had read its particles
// would show), with walls (one of them moving), periodic boundaries and a storage re-sorted every
// 7 steps; the ledger measuring on some steps, not on others.
TEST(Determinism, MotionInTheForceLoopGivesTheSeparatePassBits) {
  const int threads_before = omp_get_max_threads();
  auto run = [&](bool apart, int threads, int lagging) {
    Simulation s = make_pressed_lattice(true);
    shuffle_storage(s, 3);
    s.params.load_block = 16;
    s.params.sort_every = 7, s.params.sort_min_particles = 0;
    s.walls[1].motion.velocity = Vec3(-0.01, 0, 0);  // pressing in
    s.params.max_energy_gain = 1e9;  // on, never stopping the run
    s.ledger.on = true;
    omp_set_num_threads(threads);
    set_lagging_thread_for_tests(lagging, 50);
    set_motion_apart_for_tests(apart);
    for (int k = 0; k < 40; ++k) {
      // The ledger measures every tenth step, the last among them: on the others, a block moved
      // in the force loop keeps its state before the motion in its own buffers.
      s.ledger.measure_now = k % 10 == 9;
      s.advance();
    }
    set_motion_apart_for_tests(false);
    set_lagging_thread_for_tests(-1, 0);
    return s;
  };
  const Simulation apart = run(true, 1, -1);
  ASSERT_GT(apart.pair_contact_count(), 500u) << "the test must exercise contacts";
  ASSERT_GT(apart.wall_contact_count(), 0u);
  ASSERT_NE(apart.ledger.totals.work_walls, 0.0) << "the moving wall must press on the particles";
  ASSERT_NE(apart.ledger.totals.damping_normal, 0.0);
  ASSERT_EQ(apart.step - apart.energy_balance().step0, 40) << "the reference must stay the first step, so that steps 10, 20 and 30 measure in the loop";
  ASSERT_NE(apart.energy_balance().now.kinetic, apart.energy_balance().start.kinetic);
  for (const auto& [threads, lagging] : {std::pair{1, -1}, {3, 0}, {3, 1}, {3, 2}}) {
    const Simulation s = run(false, threads, lagging);
    const std::string what = std::to_string(threads) + " threads, thread " + std::to_string(lagging) + " lagging";
    EXPECT_TRUE(same_bits(apart.particles.x, s.particles.x)) << what;
    EXPECT_TRUE(same_bits(apart.particles.v, s.particles.v)) << what;
    EXPECT_TRUE(same_bits(apart.particles.w, s.particles.w)) << what;
    EXPECT_TRUE(same_bits(apart.particles.image, s.particles.image)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(apart.ledger.totals.damping_normal), std::bit_cast<std::uint64_t>(s.ledger.totals.damping_normal)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(apart.ledger.totals.tangential_work), std::bit_cast<std::uint64_t>(s.ledger.totals.tangential_work)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(apart.ledger.totals.work_walls), std::bit_cast<std::uint64_t>(s.ledger.totals.work_walls)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(apart.energy_balance().wall_work), std::bit_cast<std::uint64_t>(s.energy_balance().wall_work)) << what;
    const MechanicalEnergy &e_apart = apart.energy_balance().now, &e = s.energy_balance().now;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(e_apart.kinetic), std::bit_cast<std::uint64_t>(e.kinetic)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(e_apart.rotational), std::bit_cast<std::uint64_t>(e.rotational)) << what;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(e_apart.potential), std::bit_cast<std::uint64_t>(e.potential)) << what;
  }
  omp_set_num_threads(threads_before);
}

// The checkpoint of a run does not depend on its storage order either: the pressed lattice with
// walls, as built and never sorted, and shuffled and sorted every 7 steps (on two threads), writes
// checkpoints whose datasets are identical bit for bit after 60 steps (files list particles in id
// order, contacts in key order), as tests/compare_checkpoints.py compares them: read back, every
// particle and contact field. (The files' bytes may differ: HDF5 leaves some bytes of its own
// metadata unset.)
TEST(Determinism, SortedShuffledAndUnsortedRunsWriteIdenticalCheckpoints) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dem_ckpt_order_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto written = [&](bool shuffled, const std::string& name) {
    Simulation s = make_pressed_lattice(true);
    if (shuffled) {
      shuffle_storage(s, 9);
      s.params.sort_every = 7, s.params.sort_min_particles = 0;
    } else {
      s.params.sort_every = 0;
    }
    omp_set_num_threads(shuffled ? 2 : 1);
    for (int k = 0; k < 60; ++k) s.advance();
    EXPECT_EQ(s.pair_contact_count(), 2900u) << name;
    CheckpointMeta meta;
    meta.writer = "test";
    meta.scene_text = "# the pressed lattice\n";
    write_checkpoint((dir / name).string(), s, meta);
    Simulation back;
    CheckpointMeta back_meta;
    read_checkpoint((dir / name).string(), back, back_meta);
    return back;
  };
  const Simulation plain = written(false, "plain.h5"), sorted = written(true, "sorted.h5");
  std::filesystem::remove_all(dir);
  ASSERT_NE(sorted.particles.size(), 0u);
  const Particles &a = plain.particles, &b = sorted.particles;
  EXPECT_EQ(a.id, b.id);
  EXPECT_TRUE(same_bits(a.x, b.x));
  EXPECT_TRUE(same_bits(a.v, b.v));
  EXPECT_TRUE(same_bits(a.w, b.w));
  EXPECT_TRUE(same_bits(a.x_ref, b.x_ref));
  EXPECT_TRUE(same_bits(a.radius, b.radius));
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.fixed, b.fixed);
  for (const auto& [one, two] : {std::pair{&plain.pair_contacts(), &sorted.pair_contacts()}, {&plain.wall_contacts(), &sorted.wall_contacts()}}) {
    ASSERT_GT(one->size(), 0u);
    EXPECT_EQ(one->key_i, two->key_i);
    EXPECT_EQ(one->key_j, two->key_j);
    EXPECT_TRUE(same_bits(one->spring, two->spring));
    EXPECT_EQ(one->bonded, two->bonded);
  }
  EXPECT_EQ(plain.step, sorted.step);
  EXPECT_EQ(plain.time, sorted.time);
}

// The force loop's four-wide versions (simd/simd.hpp) are speed only: a run with the plain loops
// ends with the same bits (here with walls, a sparse cloud: pass 1; the four-wide law runs on
// chunks of 16 contacts or more, tests/test_simd_loops.cpp).
TEST(Determinism, FourWideLoopsGiveThePlainLoopsBits) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2 on this processor: only the plain loop runs";
  Simulation a = make_cloud(), b = make_cloud();
  set_simd_loops(false);
  for (int s = 0; s < 1500; ++s) a.advance();
  set_simd_loops(true);
  for (int s = 0; s < 1500; ++s) b.advance();
  ASSERT_GT(a.pair_contacts().size(), 0u) << "the test must exercise contacts";
  EXPECT_TRUE(same_bits(a.particles.x, b.particles.x));
  EXPECT_TRUE(same_bits(a.particles.w, b.particles.w));
  EXPECT_TRUE(same_bits(a.pair_contacts().spring, b.pair_contacts().spring));
}

// Keeping every pair contact's normal and force (SimParams::keep_pair_results) is output only: a
// run that keeps only those integrate() reads (small load blocks: many contacts between blocks
// farther apart) ends with the same bits, and its contact forces are refused until a step keeps
// them again, after which they equal the other run's.
TEST(Determinism, KeepingPairResultsIsOutputOnly) {
  omp_set_num_threads(2);
  Simulation kept = make_cloud(), lean = make_cloud();
  kept.params.load_block = lean.params.load_block = 16;
  lean.params.keep_pair_results = false;
  for (int s = 0; s < 1500; ++s) kept.advance(), lean.advance();
  ASSERT_GT(kept.pair_contacts().size(), 0u) << "the test must exercise contacts";
  EXPECT_TRUE(same_bits(kept.particles.x, lean.particles.x));
  EXPECT_TRUE(same_bits(kept.particles.v, lean.particles.v));
  EXPECT_TRUE(same_bits(kept.particles.w, lean.particles.w));
  EXPECT_TRUE(same_bits(kept.pair_contacts().spring, lean.pair_contacts().spring));
  EXPECT_FALSE(lean.pair_results_kept());
  EXPECT_THROW(contact_forces(lean, lean.particles.x), std::logic_error);
  lean.params.keep_pair_results = true;
  const std::vector<Vec3> x = kept.particles.x;
  kept.advance(), lean.advance();
  const ContactForceSet a = contact_forces(kept, x), b = contact_forces(lean, x);
  ASSERT_GT(a.pairs(), 0u);
  EXPECT_TRUE(same_bits(a.pair_force, b.pair_force));
  EXPECT_TRUE(same_bits(a.pair_normal, b.pair_normal));
}

// The skin is speed only: it sets when the neighbour list is rebuilt, and so which candidates the
// list holds, never a bit of the result (mere candidates add exact zeros; each rebuild carries
// every spring over by key: group by group between storage sorts, through a sort of the
// candidates after one). Runs with a skin of a hundredth of the smallest radius and of twice the
// largest rebuild at very different steps and end with the same bits, with the storage never
// sorted and sorted every 50 steps, with small load blocks.
TEST(Determinism, SkinChangesNoBit) {
  omp_set_num_threads(2);
  for (const long sort_every : {0L, 50L}) {
    auto run = [&](double skin) {
      Simulation s = make_cloud();
      s.params.skin = skin;
      s.params.sort_every = sort_every, s.params.sort_min_particles = 0;
      s.params.load_block = 16;
      for (int k = 0; k < 1500; ++k) s.advance();
      return s;
    };
    const Simulation thin = run(0.00001), thick = run(0.0036);
    ASSERT_GT(thin.pair_contacts().size(), 0u) << "the test must exercise contacts";
    EXPECT_GT(thin.neighbour_builds(), 3 * thick.neighbour_builds()) << "the skins must rebuild at different steps";
    EXPECT_TRUE(same_bits(thin.particles.x, thick.particles.x)) << "sort_every " << sort_every;
    EXPECT_TRUE(same_bits(thin.particles.v, thick.particles.v)) << "sort_every " << sort_every;
    EXPECT_TRUE(same_bits(thin.particles.w, thick.particles.w)) << "sort_every " << sort_every;
    EXPECT_TRUE(same_bits(thin.pair_contacts().spring, thick.pair_contacts().spring)) << "sort_every " << sort_every;
    std::printf("sort_every %ld: %lld and %lld list builds\n", sort_every, static_cast<long long>(thin.neighbour_builds()),
                static_cast<long long>(thick.neighbour_builds()));
  }
}

// Storage order is speed only (SimParams::sort_every): the falling cloud with walls, stored in
// shuffled order and sorted along the cells every 7 steps (blocks of 16 slots), ends particle by
// particle (matched by id) with the bits of the same cloud never sorted, and with the same
// contacts and springs. (Few of this sparse cloud's particles hold three contacts at once, so
// another order of the sums seldom shows here: StorageOrderAndThreadsChangeNoBit is the test that
// tells.)
// The kinetic energy a settle check stops on is summed in id order: a shuffled storage gives its
// bits (storage order would not: the sum of the terms backwards differs). The pressed lattice's
// 1000 spheres fit one block of the parallel sum (1024 particles); 12,000 random ones, as the
// settle of a generated sample, take twelve, on one and two threads.
TEST(Determinism, KineticEnergyIgnoresStorageOrder) {
  const int threads_before = omp_get_max_threads();
  Simulation big;
  big.materials = glass();
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (long k = 0; k < 12000; ++k) {
    big.particles.add(k, Vec3(u(rng), u(rng), u(rng)), 1e-3 * (1.5 + u(rng)), 2500, 0);
    big.particles.v[k] = Vec3(u(rng), u(rng), u(rng)), big.particles.w[k] = Vec3(u(rng), u(rng), 30 * u(rng));
  }
  Simulation small = make_pressed_lattice(false);
  for (std::size_t k = 0; k < small.particles.size(); ++k) small.particles.w[k] = Vec3(0.01 * k, 0, 0.3);
  for (Simulation* a : {&small, &big}) {
    Simulation b = *a;
    shuffle_storage(b, 3);
    ASSERT_NE(a->particles.id, b.particles.id);
    for (const int threads : {1, 2}) {
      omp_set_num_threads(threads);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a->kinetic_energy()), std::bit_cast<std::uint64_t>(b.kinetic_energy()))
          << a->particles.size() << " particles, " << threads << " threads";
    }
    double forward = 0, backward = 0, r;
    for (std::size_t k = 0; k < a->particles.size(); ++k) forward += kinetic_energy_of(a->particles, k, r);
    for (std::size_t k = b.particles.size(); k-- > 0;) backward += kinetic_energy_of(b.particles, k, r);
    ASSERT_NE(forward, backward) << "another order must change bits for the test to mean anything";
  }
  omp_set_num_threads(threads_before);
}

TEST(Determinism, StorageOrderChangesNoBit) {
  auto by_id = [](const Simulation& s, const std::vector<Vec3>& field) {
    std::vector<std::size_t> k(s.particles.size());
    std::iota(k.begin(), k.end(), 0);
    std::sort(k.begin(), k.end(), [&](std::size_t a, std::size_t b) { return s.particles.id[a] < s.particles.id[b]; });
    std::vector<Vec3> out;
    for (std::size_t j : k) out.push_back(field[j]);
    return out;
  };
  constexpr int kSteps = 1500;
  Simulation plain = make_cloud();
  plain.params.sort_every = 0;
  omp_set_num_threads(1);
  for (int s = 0; s < kSteps; ++s) plain.advance();
  Simulation sorted = make_cloud();
  shuffle_storage(sorted, 5);
  sorted.params.sort_every = 7;
  sorted.params.sort_min_particles = 0;
  sorted.params.load_block = 16;
  for (int s = 0; s < kSteps; ++s) sorted.advance();
  ASSERT_NE(sorted.particles.id, plain.particles.id) << "the storage orders must differ for the test to mean anything";
  ASSERT_GT(plain.pair_contacts().size(), 0u) << "the test must exercise contacts";
  EXPECT_TRUE(same_bits(by_id(plain, plain.particles.x), by_id(sorted, sorted.particles.x)));
  EXPECT_TRUE(same_bits(by_id(plain, plain.particles.v), by_id(sorted, sorted.particles.v)));
  EXPECT_TRUE(same_bits(by_id(plain, plain.particles.w), by_id(sorted, sorted.particles.w)));
  EXPECT_EQ(plain.pair_contacts().key_i, sorted.pair_contacts().key_i);
  EXPECT_EQ(plain.pair_contacts().key_j, sorted.pair_contacts().key_j);
  EXPECT_TRUE(same_bits(plain.pair_contacts().spring, sorted.pair_contacts().spring));
}

// Speed only, but where it goes wrong nothing else shows it: a run's first step sorts the storage
// (a checkpoint's particles come by id), and along the axis with the most cells first. A slab of
// 44 x 11 x 2 cells, stored shuffled and at a step that is no multiple of sort_every, comes out
// of one step with its cells in order, x varying slowest and z fastest.
TEST(StorageOrder, ARunsFirstStepSortsWithTheLongestAxisSlowest) {
  Simulation s;
  s.materials = glass();
  const double r = 1e-3;  // cells of one diameter; the spheres 2.2 r apart do not touch
  long id = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 2; ++k) s.particles.add(id++, Vec3(2.2 * r * i, 2.2 * r * j, 2.2 * r * k), r, 2500, 0);
  shuffle_storage(s, 9);
  s.dt = 0.1 * s.critical_time_step();
  s.params.gravity = Vec3::Zero();
  s.params.sort_min_particles = 0;
  s.step = 5;  // sort_every 1,000: no sort due by the step count
  s.advance();
  std::vector<std::array<long, 3>> cells;  // (x, y, z) cell of each slot in storage order
  for (const Vec3& x : s.particles.x) cells.push_back({std::lround(std::floor(x.x() / (2 * r))), std::lround(std::floor(x.y() / (2 * r))), std::lround(std::floor(x.z() / (2 * r)))});
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end())) << "storage not in (x, y, z) cell order after the first step";
  ASSERT_NE(cells.front()[0], cells.back()[0]);
}

// The threads' shares of a blocked loop (core/block_times.hpp): contiguous runs that cover every
// block once, each ending at the block boundary nearest its share of the blocks' fitted times.
TEST(BlockTimes, RunsCoverEveryBlockOnceAndEndNearestTheirShare) {
  BlockTimes t;
  t.fit(4, [](long) { return 1L; });
  EXPECT_EQ(t.total, 4);
  t.ticks = {10, 10, 10, 70};
  t.fit(4, [](long) { return 1L; });  // same count: the times stay
  EXPECT_EQ(t.total, 100);
  // Two threads: 30 / 70 is the nearest split to 50 / 50 that keeps the runs contiguous.
  EXPECT_EQ(t.run_start(0, 2), 0);
  EXPECT_EQ(t.run_start(1, 2), 3);
  EXPECT_EQ(t.run_start(2, 2), 4);
  // Blocks timed anew during the loop leave the runs as fit() cut them (a thread may time its
  // first block before another has cut its run): here the run would begin at block 4.
  t.ticks[3] = 1;
  EXPECT_EQ(t.run_start(1, 2), 3);
  // Even times: even runs; more threads than blocks: some runs are empty, none overlap.
  t.ticks.assign(6, 5);
  t.fit(6, [](long) { return 1L; });
  EXPECT_EQ(t.run_start(1, 3), 2);
  EXPECT_EQ(t.run_start(2, 3), 4);
  for (long threads : {1L, 2L, 5L, 9L}) {
    long previous = 0;
    for (long u = 0; u <= threads; ++u) {
      const long s = t.run_start(u, threads);
      EXPECT_GE(s, previous) << threads << " threads";
      previous = s;
    }
    EXPECT_EQ(t.run_start(0, threads), 0);
    EXPECT_EQ(t.run_start(threads, threads), 6);
  }
  t.fit(2, [](long b) { return 7 + b; });  // the count changed: the estimates
  EXPECT_EQ(t.ticks, (std::vector<long>{7, 8}));
}

// The fluid's force (forces/fluid.hpp) and its void fractions: the cloud in an upward flow of
// water, its void fractions updated every 7 steps, stored as built or shuffled and sorted every 5
// steps, on one, two and three threads, ends with the same bits particle by particle (matched by
// id), void fractions included; and the fluid does act (the positions differ from a run without).
TEST(Determinism, FluidChangesNoBitWithStorageOrThreads) {
  const int threads_before = omp_get_max_threads();
  auto by_id = [](const Simulation& s, const auto& field) {
    std::remove_cvref_t<decltype(field)> out(field.size());
    for (std::size_t k = 0; k < field.size(); ++k) out[s.particles.id[k]] = field[k];
    return out;
  };
  auto run = [&](bool fluid, bool shuffled, int threads) {
    Simulation s = make_cloud();
    if (fluid) {
      s.params.fluid.flow = FluidParams::Flow::Uniform;
      s.params.fluid.viscosity = 1e-3, s.params.fluid.density = 998;
      s.params.fluid.gradient = Vec3(0, 0, -2e4);
      s.params.fluid.void_cutoff = 9e-3, s.params.fluid.void_every = 7;
    }
    if (shuffled) shuffle_storage(s, 9), s.params.sort_every = 5, s.params.sort_min_particles = 0;
    omp_set_num_threads(threads);
    for (int k = 0; k < 300; ++k) s.advance();
    return s;
  };
  const Simulation one = run(true, false, 1);
  ASSERT_EQ(one.particles.void_fraction.size(), one.particles.size());
  EXPECT_FALSE(same_bits(by_id(one, one.particles.x), by_id(one, run(false, false, 1).particles.x))) << "the fluid must act";
  for (const bool shuffled : {false, true})
    for (const int threads : {1, 2, 3}) {
      if (!shuffled && threads == 1) continue;
      const Simulation s = run(true, shuffled, threads);
      const std::string what = std::string(shuffled ? "shuffled and sorted, " : "") + std::to_string(threads) + " threads";
      EXPECT_TRUE(same_bits(by_id(one, one.particles.x), by_id(s, s.particles.x))) << what;
      EXPECT_TRUE(same_bits(by_id(one, one.particles.v), by_id(s, s.particles.v))) << what;
      EXPECT_TRUE(same_bits(by_id(one, one.particles.void_fraction), by_id(s, s.particles.void_fraction))) << what;
    }
  omp_set_num_threads(threads_before);
}

}  // namespace
}  // namespace dem
