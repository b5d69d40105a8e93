// The normal dashpot in time (docs/contact-laws.md, "The dashpot in time", eq. D1-D5) against the
// closed forms of the linear spring and dashpot (bench/binary_collision.hpp), for cundall and an
// unbonded mendes contact (linear in compression): binary collisions through the whole step
// (force loop and leapfrog), two spheres head-on and a sphere on a plane wall, the first touch at
// four places within a step, at 50 steps per contact; and a bonded mendes pair's small swing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "../bench/binary_collision.hpp"

namespace dem {
namespace {

using namespace collision;

constexpr double kEtas[] = {0.05, 0.1, 0.3, 0.5, 0.9, 1.0};
constexpr double kPhases[] = {0.0, 0.25, 0.5, 0.75};

std::string what(bool wall, double eta, double phase) {
  return std::string(wall ? "wall" : "pair") + ", eta " + std::to_string(eta) + ", phase " + std::to_string(phase);
}

// Restitution, contact time and peak overlap within 1 % of the closed form (the bound; the
// scheme's error at 50 steps is measured at most 0.2 % (docs/contact-laws.md table), so a
// first-order slip, which costs 4-18 % at this step, fails it) for every eta, phase, pair and wall,
// with a normal law linear in compression.
void expect_linear_closed_form_at_fifty_steps(NormalLaw law) {
  for (const bool wall : {false, true})
    for (const double eta : kEtas) {
      const Closed ref = linear_closed_form(1e5, effective_mass(wall), eta, 0.5);
      for (const double phase : kPhases) {
        Shot s;
        s.law = law, s.wall = wall, s.eta = eta, s.steps = 50, s.t_ref = ref.duration, s.phase = phase;
        const Result r = collide(s);
        EXPECT_NEAR(r.restitution, eta, 0.01 * eta) << what(wall, eta, phase);
        EXPECT_NEAR(r.duration, ref.duration, 0.01 * ref.duration) << what(wall, eta, phase);
        EXPECT_NEAR(r.peak_overlap, ref.peak_overlap, 0.01 * ref.peak_overlap) << what(wall, eta, phase);
      }
    }
}

TEST(Restitution, LinearDashpotMatchesTheClosedFormAtFiftyStepsForEveryPhase) {
  expect_linear_closed_form_at_fifty_steps(NormalLaw::Cundall);
}

// An unbonded mendes contact is linear in compression (docs/physics.md P12: f_el = k_n u for
// u >= 0, its tension needs a bond), so its collisions meet the same closed form and bounds. With
// no bond in the scene it runs as its WithoutBonds law (materials.cpp): this pins that path too.
TEST(Restitution, UnbondedMendesMatchesTheLinearClosedFormAtFiftySteps) {
  expect_linear_closed_form_at_fifty_steps(NormalLaw::Mendes);
}

// A bonded mendes pair swinging about its bond length (docs/physics.md, after the damping table):
// linear k_n in compression, T(s) of P12 in tension, whose slope at s = 0 is k_n (L - 1). At an
// amplitude s << 1/A (here 1e-4/A: T departs from the line by L A s / (2 (L - 1)), 6e-5) it is a
// bilinear spring, each half cycle a damped linear oscillator (binary_collision.hpp's closed form):
// compression with k_n and eta, tension with k_n (L - 1) and the same dashpot, damping ratio
// gamma / sqrt(L - 1). Checked at 50 steps per (tension) half cycle, the shorter: both halves'
// durations, the peaks' ratio, and the decay of the peak over a whole swing, eta times the tension
// half's restitution, within 1 % (the unbonded test's bound; round-off at this amplitude, 1e-19 m in
// 1e-10 m, is far below).
TEST(Restitution, BondedMendesSwingsAsItsBilinearClosedFormAtFiftySteps) {
  for (const double eta : {0.3, 0.5, 0.9}) {
    Material m;
    m.name = "bonded";
    m.law = NormalLaw::Mendes;
    m.density = kDensityA;
    m.kn = m.kt = 1e5;
    m.friction_angle = 0;
    m.restitution = eta;
    m.restitution_t = 1;
    m.tensile_strength = 1;
    m.epsilon = 1e-4;
    Simulation sim;
    sim.materials = MaterialTable({m}, {});
    sim.params.gravity = Vec3::Zero();
    const PairParams& p = sim.materials.pair(0, 0);
    ASSERT_TRUE(p.mendes_tension);
    const double L = p.mendes_D * p.mendes_A, m_eff = mass(kA, kDensityA) / 2;
    const double gamma2 = damping_ratio(eta) / std::sqrt(L - 1), s2 = std::sqrt(1 - gamma2 * gamma2);
    const double eta2 = std::exp(-gamma2 * std::numbers::pi / s2);  // the tension half's restitution
    const double w2 = std::sqrt(p.kn * (L - 1) / m_eff);
    const double v = 1e-4 / p.mendes_A * w2 / eta;  // the tension half's peak about 1e-4 / A
    const Closed press = linear_closed_form(p.kn, m_eff, eta, v), pull = linear_closed_form(p.kn * (L - 1), m_eff, eta2, eta * v);
    const Closed press2 = linear_closed_form(p.kn, m_eff, eta, eta * eta2 * v);
    sim.dt = pull.duration / 50;
    sim.particles.add(0, Vec3(-kA, 0, 0), kA, kDensityA, 0);
    sim.particles.add(1, Vec3(kA, 0, 0), kA, kDensityA, 0);
    sim.particles.v[0] = Vec3(v / 2, 0, 0);  // touching, approaching at v
    sim.particles.v[1] = Vec3(-v / 2, 0, 0);
    ASSERT_EQ(sim.bond_present_contacts(false, 1e-9), 1u);
    // The zero crossings of the overlap (linear within a step; the first, the start, at the first
    // step) and each half's largest |overlap|: peak[1] the first compression, peak[2] the first
    // tension, peak[3] the second compression, peak[4] the second tension.
    const auto overlap = [&] { return 2 * kA - (sim.particles.x[1] - sim.particles.x[0]).norm(); };
    std::vector<double> cross, peak{0};
    double before = overlap();
    for (int n = 0; n < 2000 && cross.size() < 5; ++n) {
      sim.advance();
      const double now = overlap();
      if ((before > 0) != (now > 0)) cross.push_back(sim.time - sim.dt * now / (now - before)), peak.push_back(0);
      peak.back() = std::max(peak.back(), std::abs(now));
      before = now;
    }
    ASSERT_EQ(cross.size(), 5u) << "eta " << eta << ": the bond must hold and the pair swing";
    // The halves after the first, and the peaks as ratios: free of the start (the bond begins at a
    // step, the velocity given there is a half step's).
    EXPECT_NEAR(cross[2] - cross[1], pull.duration, 0.01 * pull.duration) << "eta " << eta;
    EXPECT_NEAR(cross[3] - cross[2], press.duration, 0.01 * press.duration) << "eta " << eta;
    const double ratio = press2.peak_overlap / pull.peak_overlap;
    EXPECT_NEAR(peak[3] / peak[2], ratio, 0.01 * ratio) << "eta " << eta;
    EXPECT_NEAR(peak[4] / peak[2], eta * eta2, 0.01 * eta * eta2) << "eta " << eta;
    std::printf("  bonded mendes, eta %.1f: tension half %+.1e, compression half %+.1e, peaks %+.1e, swing's decay %+.1e\n", eta,
                (cross[2] - cross[1]) / pull.duration - 1, (cross[3] - cross[2]) / press.duration - 1, peak[3] / peak[2] / ratio - 1,
                peak[4] / peak[2] / (eta * eta2) - 1);
  }
}

// Second order: halving the step divides the worst restitution error (over the phases) by about
// four. Checked from 50 to 100 and 100 to 200 steps per contact, where round-off (1e-12) is far
// below the errors (1e-4 and less); a first-order scheme gives a ratio near 2, so the bound, 3,
// tells the two apart.
TEST(Restitution, ErrorFallsAsTheSquareOfTheStep) {
  for (const bool wall : {false, true})
    for (const double eta : {0.05, 0.3}) {
      const Closed ref = linear_closed_form(1e5, effective_mass(wall), eta, 0.5);
      double err[3] = {0, 0, 0};
      for (int k = 0; k < 3; ++k)
        for (const double phase : kPhases) {
          Shot s;
          s.wall = wall, s.eta = eta, s.steps = 50 << k, s.t_ref = ref.duration, s.phase = phase;
          err[k] = std::max(err[k], std::abs(collide(s).restitution - eta));
        }
      EXPECT_GT(err[0] / err[1], 3.0) << what(wall, eta, 0) << ": " << err[0] << " " << err[1];
      EXPECT_GT(err[1] / err[2], 3.0) << what(wall, eta, 0) << ": " << err[1] << " " << err[2];
    }
}

// Restitution 0 (critical damping, gamma = 1): the overlap v t exp(-w t) never returns to zero and
// the spheres come to rest together. Through the step the overlap decays until it reaches the
// coordinates' round-off (1e-18 m against (v/w) w t exp(-w t), at w t of about 35, ten times the
// contact time t_ref of eta = 0.5 used for the step), where the contact flickers off with the
// relative speed left then, v (1 + w t) exp(-w t) (about 1e-13 v). A contact that parted early
// (a dashpot too weak at the first or last steps) would end within a few t_ref with a speed of
// order 1e-3 v or more: the bounds (the contact lasts 5 t_ref, the speed left below 1e-9 v) tell.
TEST(Restitution, RestitutionZeroIsCriticalDamping) {
  for (const bool wall : {false, true}) {
    Shot s;
    s.wall = wall, s.eta = 0, s.steps = 50;
    s.t_ref = linear_closed_form(1e5, effective_mass(wall), 0.5, 0.5).duration;
    const Result r = collide(s);
    EXPECT_LT(std::abs(r.restitution), 1e-9) << (wall ? "wall" : "pair");
    EXPECT_TRUE(r.duration == 0 || r.duration > 5 * s.t_ref) << (wall ? "wall" : "pair") << ": together for " << r.duration / s.t_ref << " t_ref";
  }
}

}  // namespace
}  // namespace dem
