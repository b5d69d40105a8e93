// Fibres (docs/physics.md eq. P60-P64): the tension-only law against its closed form, breaking,
// springs in series, a one-sided oscillator's energy and period, ties turning with their
// particle, the Love-Weber part, and the same bits for any thread count, storage order and a
// restart from a checkpoint.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "forces/fibres.hpp"
#include "generation/fibre_placement.hpp"
#include "generation/fill.hpp"
#include "io/checkpoint.hpp"
#include "post/stress.hpp"
#include "sim/simulation.hpp"
#include "simd/simd.hpp"

#include "bead_cloud.hpp"
#include "glass.hpp"
#include "same_bits.hpp"

namespace dem {
namespace {

constexpr double kRadius = 0.001;            // [m]
constexpr double kE = 3e9;                   // polypropylene-like modulus [Pa]
constexpr double kDiameter = 1e-4;           // [m]
const double kArea = std::numbers::pi * kDiameter * kDiameter / 4;

// Particles on the x axis at `xs`, far enough apart never to touch; no gravity, no damping.
Simulation row(const std::vector<double>& xs) {
  Simulation sim;
  sim.materials = glass_beads();
  sim.params.gravity = Vec3::Zero();
  for (std::size_t k = 0; k < xs.size(); ++k) sim.particles.add(static_cast<Index>(k), Vec3(xs[k], 0, 0), kRadius, 2500, 0);
  return sim;
}

// One fibre through the centres of all particles of `sim`, in id order, at rest.
void thread_through_centres(Simulation& sim, double strength) {
  std::vector<std::pair<Index, Vec3>> ties;
  std::vector<double> rest;
  for (std::size_t k = 0; k < sim.particles.size(); ++k) {
    ties.emplace_back(sim.particles.id[k], Vec3::Zero());
    if (k > 0) rest.push_back((sim.particles.x[k] - sim.particles.x[k - 1]).norm());
  }
  sim.fibres.add(ties, rest, kArea, kE, strength);
}

// (1) One fibre between a held particle and one prescribed to move away at constant speed: the
// force on the held one is EA/L0 x extension, the extension measured from the two positions at
// which the step computed its forces. Tolerance 1e-9 relative: the law is one multiplication and
// the extension a difference of two positions of about L0 = 10 mm, exact to ~1e-18 m against
// extensions of 1e-6 m and more (1e-12 relative); 1e-9 leaves room and still fails any wrong
// factor. Once the tension would pass sigma_t A the segment breaks: zero from then on, also after
// the particle comes back. Pushed together from the start: no force at all.
TEST(Fibres, PulledApartAtConstantSpeedFollowsEAOverL0UntilItBreaks) {
  const double L0 = 0.01, speed = 0.05;
  const double strength = 2e7;  // sigma_t [Pa]: breaks at strain sigma_t / E = 6.7e-3
  Simulation sim = row({0, L0});
  thread_through_centres(sim, strength);
  sim.particles.fixed = {kHeld, kPrescribed};
  sim.particles.v[1] = Vec3(speed, 0, 0);
  sim.dt = 1e-5;  // 5e-7 m per step: the break strain 6.7e-3 x L0 = 6.7e-5 m is reached after ~133 steps
  const double ea = kE * kArea, limit = strength * kArea;
  bool broke = false;
  int loaded_steps = 0;
  for (int n = 0; n < 400; ++n) {
    if (n == 300) sim.particles.v[1] = Vec3(-speed, 0, 0);  // back again: still nothing once broken
    const double extension = (sim.particles.x[1] - sim.particles.x[0]).norm() - L0;
    sim.advance();
    const Vec3 f = sim.net_force(0);
    const double expected = ea / L0 * extension;
    if (!broke && expected <= limit) {
      if (extension > 0) {
        ++loaded_steps;
        EXPECT_NEAR(f.x(), expected, 1e-9 * expected) << "step " << n;
      } else {
        EXPECT_EQ(f.x(), 0.0) << "step " << n;
      }
      EXPECT_EQ(f.y(), 0.0);
      EXPECT_EQ(f.z(), 0.0);
    } else {
      broke = true;
      EXPECT_EQ(f.norm(), 0.0) << "step " << n << ": a broken fibre carries nothing";
      EXPECT_EQ(sim.fibres.broken[0], 1);
    }
  }
  EXPECT_TRUE(broke);
  EXPECT_GT(loaded_steps, 100);
  // The closed form of the run: the extension at the break is sigma_t L0 / E, reached at t = that / speed.
  EXPECT_NEAR(loaded_steps * sim.dt * speed, strength * L0 / kE, 2 * speed * sim.dt);
}

TEST(Fibres, PushedTogetherCarriesNothing) {
  const double L0 = 0.01;
  Simulation sim = row({0, L0});
  thread_through_centres(sim, 1e9);
  sim.particles.fixed = {kHeld, kPrescribed};
  sim.particles.v[1] = Vec3(-0.05, 0, 0);
  sim.dt = 1e-5;
  for (int n = 0; n < 100; ++n) {  // 5 mm closer, spheres still apart
    sim.advance();
    EXPECT_EQ(sim.net_force(0).norm(), 0.0) << "step " << n;
    EXPECT_EQ(sim.fibres.tension[0], 0.0);
  }
  EXPECT_EQ(sim.fibres.broken[0], 0);
}

// (2) A fibre through five particles in a row, the two ends pulled apart and then held, the three
// inner ones free under global damping: at rest every segment carries the same tension, that of
// springs in series, EA (L - L_0) / L_0 with L the length between the ends and L_0 the sum of the
// rest lengths. Tolerance 1e-9 relative: after 40,000 steps (0.08 s) of strong global damping
// (alpha_r = 2e4 1/s: every mode of the chain decays faster than 1e4 1/s) the motion left is
// below round-off.
TEST(Fibres, FiveInARowPulledAtBothEndsCarryEqualTensionAtRest) {
  const double s = 0.004;
  Simulation sim = row({0, s, 2 * s, 3 * s, 4 * s});
  // Unequal rest lengths would still give equal tensions; equal ones keep the picture simple.
  thread_through_centres(sim, 1e12);
  sim.particles.fixed = {kPrescribed, kFree, kFree, kFree, kPrescribed};
  sim.particles.v[0] = Vec3(-0.01, 0, 0);
  sim.particles.v[4] = Vec3(0.01, 0, 0);
  sim.params.alpha_r = 2e4;
  sim.dt = 0.1 * sim.critical_time_step();
  for (int n = 0; n < 2000; ++n) sim.advance();
  sim.particles.v[0] = sim.particles.v[4] = Vec3::Zero();  // held from now on
  for (int n = 0; n < 40000; ++n) sim.advance();
  const double length = sim.particles.x[4].x() - sim.particles.x[0].x(), rest = 4 * s;
  ASSERT_GT(length, rest * 1.001);
  const double expected = kE * kArea * (length - rest) / rest;
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(sim.fibres.tension[k], expected, 1e-9 * expected) << "segment " << k;
}

// An undamped particle between two held ones, tied by one fibre through the three centres: each
// segment pulls only when stretched, so the middle one feels -k x on either side, k = EA/L0: a
// harmonic oscillator made of two one-sided springs. The central-difference step conserves
// E_n = m/2 v_{n-1/2}.v_{n+1/2} + k/2 x_n^2 exactly for a linear spring (its discrete invariant),
// so over 1,000 periods at 40 steps a period E changes by round-off alone: tolerance 1e-6
// relative. The period against the closed form of the discrete oscillator, T = 2 pi / w_d with
// w_d = (2/dt) asin(w dt/2), w = sqrt(k/m): within 1e-6 relative (zero crossings interpolated
// linearly over 1,000 periods).
TEST(Fibres, OneSidedOscillatorKeepsItsEnergyFor1000Periods) {
  const double L0 = 0.005;
  Simulation sim = row({0, L0, 2 * L0});
  thread_through_centres(sim, 1e12);
  sim.particles.fixed = {kHeld, kFree, kHeld};
  const double m = sim.particles.mass[1], k = kE * kArea / L0, w = std::sqrt(k / m);
  sim.dt = 2 * std::numbers::pi / w / 40;
  sim.particles.v[1] = Vec3(1e-3 * L0 * w, 0, 0);  // amplitude 0.1 % of L0
  const auto energy = [&](double x, const Vec3& v_before, const Vec3& v_after) { return 0.5 * m * v_before.dot(v_after) + 0.5 * k * x * x; };
  double e0 = 0, worst = 0, first_crossing = -1, last_crossing = -1;
  int crossings = 0;
  for (long n = 0; n < 40L * 1000; ++n) {
    const double x = sim.particles.x[1].x() - L0;
    const Vec3 v_before = sim.particles.v[1];
    sim.advance();
    const double e = energy(x, v_before, sim.particles.v[1]);
    if (n == 0) e0 = e;
    worst = std::max(worst, std::abs(e - e0) / e0);
    const double x_next = sim.particles.x[1].x() - L0;
    if (x < 0 && x_next >= 0) {  // an upward crossing between t_n and t_n+1
      const double t = (n + x / (x - x_next)) * sim.dt;
      if (first_crossing < 0) first_crossing = t;
      last_crossing = t, ++crossings;
    }
  }
  EXPECT_LT(worst, 1e-6);
  ASSERT_GT(crossings, 900);
  const double period = (last_crossing - first_crossing) / (crossings - 1);
  const double discrete = 2 * std::numbers::pi / (2 / sim.dt * std::asin(w * sim.dt / 2));
  EXPECT_NEAR(period, discrete, 1e-6 * discrete);
}

// A tie is fixed in its particle: a particle spinning at w about z for time t carries its tie
// offset round by the angle w t (closed form: the rotation of the offset). Tolerance 1e-12 m on
// an offset of 1 mm: each step's rotation is exact to round-off, 1000 of them ~1e-16 m each.
TEST(Fibres, TiesTurnWithTheirParticle) {
  Simulation sim = row({0, 0.01});
  sim.fibres.add({{0, Vec3(kRadius * 0.9, 0, 0)}, {1, Vec3::Zero()}}, {0.01 - kRadius * 0.9}, kArea, kE, 1e9);
  sim.particles.fixed = {kPrescribed, kHeld};
  const double spin = 30;  // [rad/s]
  sim.particles.w[0] = Vec3(0, 0, spin);
  sim.dt = 1e-5;
  for (int n = 0; n < 1000; ++n) sim.advance();
  const double angle = spin * 1000 * sim.dt;
  const Vec3 expected = kRadius * 0.9 * Vec3(std::cos(angle), std::sin(angle), 0);
  EXPECT_LT((sim.fibres.tie_offset[0] - expected).norm(), 1e-12);
}

// (3) The fibres' Love-Weber part by hand: two particles 10 mm apart on x, a fibre tied 0.5 mm off
// their centres along y (so the tie line is parallel to x), stretched by 1e-5 m: T = EA/L0 x 1e-5,
// and the box average holds sigma_xx = T x 10 mm / V (tension positive), sigma_xy = 0; nothing
// else. Tolerance 1e-12 relative: a handful of operations.
TEST(Fibres, LoveWeberPartOfAKnownTension) {
  const double d = 0.01, stretch = 1e-5;
  Simulation sim = row({0, d});
  const Vec3 off(0, 0.0005, 0);
  sim.fibres.add({{0, off}, {1, off}}, {d - stretch}, kArea, kE, 1e12);
  FibreSet f = sim.fibres;
  compute_fibre_tensions(f, sim.particles, sim.periodic);
  const double t = kE * kArea / (d - stretch) * stretch;
  ASSERT_NEAR(f.tension[0], t, 1e-12 * t);
  ParticleStress ps;
  ps.moment.assign(2, Mat3::Zero());
  ps.contacts.assign(2, 0);
  add_fibre_stress(sim.particles, sim.periodic, f, ps);
  const Box box{Vec3(-0.005, -0.005, -0.005), Vec3(0.015, 0.005, 0.005)};
  const BoxAverage avg = box_average(sim.particles, ps, box);
  const double sxx = t * d / box.volume();
  EXPECT_NEAR(avg.contact(0, 0), sxx, 1e-12 * sxx);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (a + b > 0) EXPECT_EQ(avg.contact(a, b), 0.0) << a << b;
}

// A cloud of 200 beads settling in a box, with fibres as long as the box placed through it (each
// spanning many cells of the linked-cell search, tied to many particles): the same bits on one
// and two threads, with the storage shuffled and re-sorted every 7 steps, and after a restart
// from a checkpoint half way.
Simulation fibre_cloud() {
  Simulation sim = bead_cloud();
  FibreSpec fs;
  fs.count = 6;
  fs.length_min = 0.02, fs.length_max = 0.04;
  fs.diameter = 1e-4, fs.youngs_modulus = 1e8, fs.tensile_strength = 3e6;
  fs.seed = 5;
  const FibrePlacement placed = place_fibres(sim.particles, fs, sim.fibres);
  EXPECT_EQ(placed.placed, 6u);
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

struct FibreRun {
  Simulation sim;
  std::vector<Vec3> x, v, w, offset;  // in id order
  std::vector<double> tension;
  std::vector<std::uint8_t> broken;
};

FibreRun finish(Simulation s) {
  FibreRun r{std::move(s), {}, {}, {}, {}, {}, {}};
  for (std::size_t k : r.sim.particles.slots_by_id())
    r.x.push_back(r.sim.particles.x[k]), r.v.push_back(r.sim.particles.v[k]), r.w.push_back(r.sim.particles.w[k]);
  r.offset = r.sim.fibres.tie_offset, r.tension = r.sim.fibres.tension, r.broken = r.sim.fibres.broken;
  return r;
}

void expect_same(const FibreRun& a, const FibreRun& b, const std::string& what) {
  EXPECT_TRUE(same_bits(a.x, b.x)) << what;
  EXPECT_TRUE(same_bits(a.v, b.v)) << what;
  EXPECT_TRUE(same_bits(a.w, b.w)) << what;
  EXPECT_TRUE(same_bits(a.offset, b.offset)) << what;
  EXPECT_TRUE(same_bits(a.tension, b.tension)) << what;
  EXPECT_EQ(a.broken, b.broken) << what;
}

TEST(Fibres, LongFibresGiveTheSameBitsForThreadsStorageAndRestart) {
  const int steps = 400;
  Simulation base = fibre_cloud();
  ASSERT_GE(base.fibres.ties(), 6u * 2);
  omp_set_num_threads(1);
  Simulation one = base;
  one.params.sort_every = 0;
  double loaded = 0;  // the largest tension of the run
  for (int n = 0; n < steps; ++n) {
    one.advance();
    for (double t : one.fibres.tension) loaded = std::max(loaded, t);
  }
  const FibreRun plain = finish(one);
  EXPECT_GT(loaded, 0.0) << "the fibres must carry something for the comparison to mean anything (" << one.fibres.broken_count() << " of "
                         << one.fibres.segments() << " segments broken)";

  omp_set_num_threads(2);
  Simulation two = base;
  std::vector<std::size_t> order(two.particles.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = order.size() - 1 - k;  // reversed storage
  two.particles.reorder(order);
  two.params.sort_every = 7, two.params.sort_min_particles = 0, two.params.load_block = 16;
  for (int n = 0; n < steps; ++n) two.advance();
  expect_same(plain, finish(two), "two threads, storage reversed and sorted every 7 steps");

  // Restart half way through a checkpoint.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("dem_fibres_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  Simulation first = base;
  first.params.sort_every = 0;
  for (int n = 0; n < steps / 2; ++n) first.advance();
  CheckpointMeta meta;
  meta.writer = "test";
  meta.scene_text = "# fibres\n";
  write_checkpoint((dir / "half.h5").string(), first, meta);
  Simulation back;
  CheckpointMeta back_meta;
  read_checkpoint((dir / "half.h5").string(), back, back_meta);
  std::filesystem::remove_all(dir);
  back.materials = first.materials;
  back.params = first.params;
  ASSERT_EQ(back.fibres.segments(), first.fibres.segments());
  for (int n = 0; n < steps / 2; ++n) back.advance();
  omp_set_num_threads(1);
  expect_same(plain, finish(back), "restarted from a checkpoint half way");
}

// A tie whose particle has gone stays gone: resolve() searches the ids when the storage changes (the
// first step, the removal), not again every step after it (it did: a sort of all particles per
// step once one tie's particle had left). The fibre's other segments keep pulling.
TEST(Fibres, ATieWhoseParticleIsGoneDoesNotMakeEveryStepSearch) {
  Simulation sim = fibre_cloud();
  sim.params.sort_every = 0;  // the storage changes only by the removal
  std::vector<char> gone(sim.particles.size());
  for (std::size_t k = 0; k < gone.size(); ++k) gone[k] = sim.particles.id[k] == sim.fibres.tie_id[1];
  std::size_t pulled = 0;
  for (int n = 0; n < 200; ++n) {
    if (n == 20) ASSERT_EQ(remove_marked(sim, gone), 1u);
    sim.advance();
    if (n >= 20) pulled += std::count_if(sim.fibres.tension.begin(), sim.fibres.tension.end(), [](double t) { return t > 0; });
  }
  EXPECT_EQ(sim.fibres.tie_slot[1], FibreSet::kGone);
  EXPECT_EQ(sim.fibres.searches, 2u) << "one search for the first step, one after the removal";
  for (std::size_t k = 0; k < sim.fibres.segments(); ++k)
    if (sim.fibres.tie_of[k] == 1 || sim.fibres.tie_of[k] + 1 == 1) EXPECT_TRUE(sim.fibres.broken[k]) << "segment " << k << " at the gone tie";
  EXPECT_GT(pulled, 0u) << "the other segments still pull";
}

// The four-wide loops (rotate_ties, add_fibre_forces: simd/simd.hpp) against the plain ones, bit for
// bit, on the fibre cloud: segments slack, pulled and breaking (weak fibres), fours that hold a
// broken segment, and a particle removed part way (its ties gone, their segments broken).
TEST(Fibres, FourWideLoopsGiveThePlainBits) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2: only the plain loops run here";
  omp_set_num_threads(1);
  for (const double strength : {3e6, 3e5}) {
    std::vector<FibreRun> runs;
    std::size_t broken = 0, pulled = 0;
    for (const bool wide : {false, true}) {
      set_simd_loops(wide);
      Simulation sim = fibre_cloud();
      sim.fibres.strength.assign(sim.fibres.fibres(), strength);
      sim.fibres.index();
      for (int n = 0; n < 400; ++n) {
        if (n == 200) {  // the particle of the first fibre's second tie leaves
          std::vector<char> gone(sim.particles.size());
          for (std::size_t k = 0; k < gone.size(); ++k) gone[k] = sim.particles.id[k] == sim.fibres.tie_id[1];
          ASSERT_EQ(remove_marked(sim, gone), 1u);
        }
        sim.advance();
        for (double t : sim.fibres.tension) pulled += t > 0;
      }
      broken = sim.fibres.broken_count();
      runs.push_back(finish(std::move(sim)));
    }
    set_simd_loops(true);
    expect_same(runs[0], runs[1], "four-wide against plain, strength " + std::to_string(strength));
    EXPECT_GT(pulled, 0u) << "the comparison must see segments pulling";
    if (strength < 1e6) EXPECT_GT(broken, 1u) << "the weak fibres must break (the removed particle breaks one)";
  }
}

}  // namespace
}  // namespace dem
