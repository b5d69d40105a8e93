// The step of motion (integrate/motion.hpp): four particles at a time (AVX2) must give the bits of one
// by one, and both the definition of eq. 2.38-2.47 written out here, coordinate by coordinate:
// v' = (a_r v + F dt / m) b_r with F the net load of the force loop, w' likewise with
// I = 2/5 m a^2, x' = x + v' dt; held particles stop; the last particle whose state is not finite
// is reported; particles that leave a periodic box come back in at the other side; the loads
// are only read.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "integrate/motion.hpp"
#include "simd/simd.hpp"

#include "same_bits.hpp"

namespace dem {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// 1,003 particles (groups of four and a remainder) with random states and loads; every 7th held.
struct MotionCase {
  std::vector<Vec3> x, v, w;
  std::vector<LoadSum> force, torque;  // their fourth doubles NaN: never read
  std::vector<Vec3i> image;
  std::vector<double> mass, radius;
  std::vector<std::uint8_t> fixed;
  MotionConstants c{0.9995, 1 / 1.0005, 0.998, 1 / 1.002, 1e-5};

  // Periodic: in x and z over [0, 1), every third particle about to leave through x = 1, every
  // fifth through z = 0 (a step moves them 1e-6).
  explicit MotionCase(long n, bool periodic = false) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto vec = [&](double s) { return Vec3(s * u(rng), s * u(rng), s * u(rng)); };
    for (long i = 0; i < n; ++i) {
      x.push_back(vec(1)), v.push_back(vec(0.1)), w.push_back(vec(10)), force.push_back({vec(1e-3), kNaN}), torque.push_back({vec(1e-6), kNaN});
      image.push_back(Vec3i(1, -2, 3));
      if (periodic) {
        x.back() = x.back().cwiseAbs();
        if (i % 3 == 0) x.back().x() = 1 - 5e-7, v.back().x() = 0.1;
        if (i % 5 == 0) x.back().z() = 5e-7, v.back().z() = -0.1;
      }
      mass.push_back(1e-5 * (1.5 + u(rng))), radius.push_back(1e-3 * (1.5 + u(rng)));
      fixed.push_back(i % 7 == 3);
    }
    if (periodic) c.box.axis = {true, false, true}, c.box.lo = Vec3::Zero(), c.box.hi = Vec3::Ones();
  }
  MotionArrays arrays(bool any_fixed) {
    return {.x = x.data(),
            .v = v.data(),
            .w = w.data(),
            .image = image.data(),
            .mass = mass.data(),
            .radius = radius.data(),
            .fixed = any_fixed ? fixed.data() : nullptr,
            .force = force.data(),
            .torque = torque.data()};
  }
};

// What a step gives particle i, by the definition.
struct Expected {
  Vec3 x, v, w;
  Vec3i image;
};
Expected definition(const MotionCase& m, long i, bool any_fixed) {
  if (any_fixed && m.fixed[i]) return {m.x[i], Vec3::Zero(), Vec3::Zero(), m.image[i]};
  Expected e{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), m.image[i]};
  for (int d = 0; d < 3; ++d) {
    const double f = m.force[i].v[d], t = m.torque[i].v[d];
    const double inertia = 0.4 * m.mass[i] * m.radius[i] * m.radius[i];
    e.v[d] = (m.c.ar * m.v[i][d] + f * (m.c.dt / m.mass[i])) * m.c.br;
    e.w[d] = (m.c.at * m.w[i][d] + t * (m.c.dt / inertia)) * m.c.bt;
    e.x[d] = m.x[i][d] + e.v[d] * m.c.dt;
    if (!m.c.box.axis[d]) continue;
    if (e.x[d] >= 1) e.x[d] -= 1, ++e.image[d];
    else if (e.x[d] < 0) e.x[d] += 1, --e.image[d];
  }
  return e;
}

const std::vector<int>& widths() {
  static const std::vector<int> w = simd_loops_available() ? std::vector<int>{0, 1} : std::vector<int>{0};
  return w;
}

TEST(Motion, FourAtATimeGiveTheDefinitionsBits) {
  for (bool periodic : {false, true})
    for (bool any_fixed : {false, true})
      for (auto [first, last] : {std::pair<long, long>{0, 1003}, {1, 6}, {498, 523}, {5, 7}}) {
        std::vector<MotionCase> runs;
        for (int simd : widths()) {
          MotionCase m(1003, periodic);
          set_simd_loops(simd);
          EXPECT_EQ(move_particles(m.arrays(any_fixed), m.c, first, last), -1);
          runs.push_back(std::move(m));
        }
        set_simd_loops(true);
        const MotionCase before(1003, periodic);
        int wrapped = 0;
        for (const MotionCase& m : runs)
          for (long i = 0; i < 1003; ++i) {
            const bool moved = i >= first && i < last;
            const Expected e =
                moved ? definition(before, i, any_fixed) : Expected{before.x[i], before.v[i], before.w[i], before.image[i]};
            const std::string what = "particle " + std::to_string(i) + (any_fixed ? ", held ones" : "") + (periodic ? ", periodic" : "");
            ASSERT_EQ(m.x[i], e.x) << what;
            ASSERT_EQ(m.v[i], e.v) << what;
            ASSERT_EQ(m.w[i], e.w) << what;
            ASSERT_EQ(m.image[i], e.image) << what;
            ASSERT_EQ(m.force[i].v, before.force[i].v) << what;
            ASSERT_EQ(m.torque[i].v, before.torque[i].v) << what;
            wrapped += e.image != before.image[i];
          }
        if (periodic && last - first > 100) EXPECT_GT(wrapped, 200) << "the case must move particles across the boundaries";
        if (runs.size() == 2) {
          EXPECT_TRUE(same_bits(runs[0].x, runs[1].x));
          EXPECT_TRUE(same_bits(runs[0].v, runs[1].v));
          EXPECT_TRUE(same_bits(runs[0].w, runs[1].w));
        }
      }
}

// The contacts' work the motion takes as it moves (MotionWork, state/particle_work.hpp): each
// particle's sums times its mean velocities v̄ = (v before + v after)/2 and w̄, by the definition
// (docs/physics.md eq. P33-P34, P41: D · v̄ Δt, (T · v̄ + a A · w̄) Δt, M · w̄ Δt), summed exactly:
// four at a time as one by one, with couples and without, held particles among them or not, over
// ranges within one of the motion's runs of 256 particles and across them, ending in one to three
// particles past a group of four.
TEST(Motion, TakesTheContactsWorkOfTheDefinitionAsItMoves) {
  const long n = 1003;
  ParticleWorkArrays sums;
  sums.resize(n);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto vec = [&](double s) { return Vec3(s * u(rng), s * u(rng), s * u(rng)); };
  for (long i = 0; i < n; ++i)
    sums.damping[i].v = vec(1e-3), sums.tangential[i].v = vec(1e-3), sums.torque_per_radius[i].v = vec(1e-3), sums.couple[i].v = vec(1e-6);
  const auto dot = [](const Vec3& a, const Vec3& b) { return (a.x() * b.x() + a.y() * b.y()) + a.z() * b.z(); };
  for (bool couples : {false, true})
    for (bool any_fixed : {false, true})
      for (auto [first, last] : {std::pair<long, long>{0, 1003}, {1, 6}, {498, 523}, {250, 517}}) {
        const std::string what = std::string(couples ? "couples" : "no couples") + (any_fixed ? ", held ones" : "") + ", particles " +
                                 std::to_string(first) + " to " + std::to_string(last);
        // By the definition, from the state before the step.
        const MotionCase before(n);
        FixedSum damping, tangential, rolling;
        for (long i = first; i < last; ++i) {
          const Expected e = definition(before, i, any_fixed);
          Vec3 v, w;
          for (int d = 0; d < 3; ++d) v[d] = 0.5 * (before.v[i][d] + e.v[d]), w[d] = 0.5 * (before.w[i][d] + e.w[d]);
          damping.add(dot(sums.damping[i].v, v) * before.c.dt);
          tangential.add((dot(sums.tangential[i].v, v) + before.radius[i] * dot(sums.torque_per_radius[i].v, w)) * before.c.dt);
          if (couples) rolling.add(dot(sums.couple[i].v, w) * before.c.dt);
        }
        ASSERT_NE(damping.value(), 0.0) << what;
        for (int simd : widths()) {
          MotionCase m(n);
          set_simd_loops(simd);
          StepWork s;
          const MotionWork work{sums.view().from(first), couples, &s};
          EXPECT_EQ(move_particles(m.arrays(any_fixed), m.c, first, last, &work), -1) << what;
          set_simd_loops(true);
          const std::string how = what + (simd ? ", four at a time" : ", one by one");
          EXPECT_EQ(std::bit_cast<std::uint64_t>(s.damping.value()), std::bit_cast<std::uint64_t>(damping.value())) << how;
          EXPECT_EQ(std::bit_cast<std::uint64_t>(s.tangential.value()), std::bit_cast<std::uint64_t>(tangential.value())) << how;
          EXPECT_EQ(std::bit_cast<std::uint64_t>(s.rolling.value()), std::bit_cast<std::uint64_t>(rolling.value())) << how;
          // The motion itself as without the work (Motion.FourAtATimeGiveTheDefinitionsBits).
          for (long i = first; i < last; ++i) ASSERT_EQ(m.v[i], definition(before, i, any_fixed).v) << how << ", particle " << i;
        }
      }
}

// A NaN, an infinity or a coordinate beyond the largest double after the step: the last such
// particle is reported, four at a time as one by one.
TEST(Motion, ReportsTheLastParticleWhoseStateIsNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int simd : widths()) {
    set_simd_loops(simd);
    for (long bad : {0L, 2L, 5L, 998L, 1002L}) {
      MotionCase m(1003);
      m.force[bad / 2].v.x() = nan;  // an earlier one, in another group or the same
      m.torque[bad].v.z() = inf;
      EXPECT_EQ(move_particles(m.arrays(false), m.c, 0, 1003), bad) << (simd ? "four at a time" : "one by one");
      MotionCase large(1003);
      large.x[bad] = Vec3(0, 0.9 * std::numeric_limits<double>::max(), 0);
      large.v[bad] = Vec3(0, 0.2 * std::numeric_limits<double>::max(), 0);  // x and v stay finite, x + v does not
      EXPECT_TRUE(std::isfinite(large.x[bad].y() + large.v[bad].y() * large.c.dt));
      EXPECT_EQ(move_particles(large.arrays(false), large.c, 0, 1003), bad) << (simd ? "four at a time" : "one by one");
    }
  }
  set_simd_loops(true);
}

}  // namespace
}  // namespace dem
