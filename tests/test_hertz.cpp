// The hertz normal law (docs/contact-laws.md eq. H1-H4) against its closed forms: the force of an
// unlike pair, and elastic impacts (sphere on sphere, sphere on a wall) through the whole step,
// whose peak overlap, duration and rebound follow from energy conservation alone:
// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), t_c = 2.9432751843 delta_max / v (the constant
// is 2 B(2/5, 1/2) / (5/2), Johnson, Contact Mechanics, §11.1), rebound speed = v.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/contact_law.hpp"
#include "contact/model_table.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

Material hertz_material(const char* name, double young, double poisson, double density) {
  Material m;
  m.name = name;
  m.law = NormalLaw::Hertz;
  m.young_modulus = young;
  m.poisson_ratio = poisson;
  m.density = density;
  m.kt = 1e4;
  m.friction_angle = 0;
  m.restitution = 1;
  m.restitution_t = 1;
  return m;
}

const Material kSoft = hertz_material("soft", 1e7, 0.25, 2500);
const Material kHard = hertz_material("hard", 5e7, 0.3, 7800);

double effective_modulus(const Material& a, const Material& b) {  // eq. H2 by hand
  return 1 / ((1 - a.poisson_ratio * a.poisson_ratio) / a.young_modulus + (1 - b.poisson_ratio * b.poisson_ratio) / b.young_modulus);
}

// The pair's constants and the law's force, against 4/3 E* sqrt(R*) u^(3/2) written out here:
// round-off only (1e-13 relative).
TEST(Hertz, ForceOfAnUnlikePairIsTheClosedForm) {
  const MaterialTable table({kSoft, kHard}, {});
  const PairParams& p = table.pair(0, 1);
  const double e_star = effective_modulus(kSoft, kHard);
  EXPECT_NEAR(p.hertz_modulus, 4.0 / 3.0 * e_star, 1e-13 * e_star);
  const double r_eff = 1e-3 * 1.5e-3 / (1e-3 + 1.5e-3);
  for (const double u : {1e-7, 3e-6, 2e-5}) {
    ContactKinematics c;
    c.n = Vec3(0, 0, 1);
    c.overlap = u;
    c.v_rel = c.w_arm = Vec3::Zero();
    c.m_eff = 1e-5;
    c.r_eff = r_eff;
    Vec3 spring = Vec3::Zero();
    std::uint8_t bonded = 0;
    const double f = -ContactModel<HertzNormal>::evaluate(p, c, 1e-6, spring, bonded).on_i.z();
    const double expected = 4.0 / 3.0 * e_star * std::sqrt(r_eff) * std::pow(u, 1.5);
    EXPECT_NEAR(f, expected, 1e-13 * expected) << "u = " << u;
  }
  ContactKinematics apart{Vec3(0, 0, 1), -1e-6, Vec3::Zero(), Vec3::Zero(), 1e-5, r_eff};
  Vec3 spring = Vec3::Zero();
  std::uint8_t bonded = 0;
  EXPECT_EQ(ContactModel<HertzNormal>::evaluate(p, apart, 1e-6, spring, bonded).on_i, Vec3::Zero()) << "no tension";
}

struct Impact {
  double peak_overlap, duration, rebound;  // rebound: speed after / speed before
};

// A soft sphere (radius 1 mm) meets a hard one (1.5 mm) head-on at relative speed v, or a hard
// wall; no gravity, no damping. The step is t_c / steps_per_contact.
Impact impact(bool against_wall, double steps_per_contact, double v, double& t_c, double& delta_max) {
  Simulation sim;
  sim.materials = MaterialTable({kSoft, kHard}, {});
  sim.params.gravity = Vec3::Zero();
  const double a = 1e-3, b = 1.5e-3;
  const double m_a = kSoft.density * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  const double m_b = kHard.density * 4.0 / 3.0 * std::numbers::pi * b * b * b;
  const double m_eff = against_wall ? m_a : m_a * m_b / (m_a + m_b);
  const double r_eff = against_wall ? a : a * b / (a + b);
  const double e_star = effective_modulus(kSoft, kHard);
  delta_max = std::pow(15 * m_eff * v * v / (16 * e_star * std::sqrt(r_eff)), 0.4);
  t_c = 2.9432751843247047 * delta_max / v;
  sim.dt = t_c / steps_per_contact;
  const double gap = 3.3 * v * sim.dt;  // the first touch falls within a step
  if (against_wall) {
    sim.walls.push_back(Wall{"floor", 1, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
    sim.particles.add(0, Vec3(0, 0, a + gap), a, kSoft.density, 0);
    sim.particles.v[0] = Vec3(0, 0, -v);
  } else {
    sim.particles.add(0, Vec3(0, 0, a + b + gap), a, kSoft.density, 0);
    sim.particles.add(1, Vec3(0, 0, 0), b, kHard.density, 1);
    sim.particles.v[0] = Vec3(0, 0, -v * m_b / (m_a + m_b));  // centre of mass at rest
    sim.particles.v[1] = Vec3(0, 0, v * m_a / (m_a + m_b));
  }
  const auto overlap = [&] {
    return against_wall ? a - sim.particles.x[0].z() : a + b - (sim.particles.x[0] - sim.particles.x[1]).norm();
  };
  const auto approach_speed = [&] { return against_wall ? -sim.particles.v[0].z() : sim.particles.v[1].z() - sim.particles.v[0].z(); };
  Impact r{0, 0, 0};
  double before = overlap(), t_in = -1;
  for (int s = 0; s < 100 * steps_per_contact; ++s) {
    sim.advance();
    const double now = overlap();
    r.peak_overlap = std::max(r.peak_overlap, now);
    // Touch and release: the zero crossings of the overlap, interpolated within the step.
    if (before <= 0 && now > 0) t_in = sim.time - sim.dt * now / (now - before);
    if (before > 0 && now <= 0) {
      r.duration = sim.time - sim.dt * now / (now - before) - t_in;
      break;
    }
    before = now;
  }
  r.rebound = -approach_speed() / v;
  return r;
}

// At 50 steps per contact the central-difference scheme misses by 2.0e-4 (duration), 2.8e-5
// (peak overlap) and 3.5e-5 (rebound), and each error falls fourfold when the step halves (second
// order: 5.0e-5, 6.3e-6, 6.0e-6 at 100 steps). The bounds, 1e-3 and 2e-4, leave room for
// round-off and the phase of the first touch while a first-order slip (an error of about 1/50)
// fails them; the halving check catches a scheme that is only first order.
TEST(Hertz, ElasticImpactsMatchTheClosedForm) {
  for (const bool wall : {false, true}) {
    const char* what = wall ? "sphere on a wall" : "sphere on a sphere";
    double t_c = 0, delta_max = 0;
    const Impact r = impact(wall, 50, 0.2, t_c, delta_max);
    EXPECT_NEAR(r.peak_overlap, delta_max, 1e-3 * delta_max) << what;
    EXPECT_NEAR(r.duration, t_c, 1e-3 * t_c) << what;
    EXPECT_NEAR(r.rebound, 1.0, 2e-4) << what;
    const Impact fine = impact(wall, 100, 0.2, t_c, delta_max);
    EXPECT_LT(std::abs(fine.duration / t_c - 1), std::abs(r.duration / t_c - 1) / 3) << what << ": second order";
  }
}

}  // namespace
}  // namespace dem
