// The start checks of a run (run/start_checks.hpp): what they find at step 0 and how a blow-up
// lists it, most likely first, before the core's time-step advice. Each case is built so that one
// cause is certain; a sphere resting on a still plate has none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "run/start_checks.hpp"

namespace dem {
namespace {

constexpr double kRadius = 0.01;  // m

Material ball() {
  Material m;
  m.name = "ball";
  m.density = 2000;
  m.kn = m.kt = 1e5;
  m.restitution = m.restitution_t = 0.5;
  return m;
}

Simulation plate_scene(const WallMotion& motion = {}) {
  Simulation sim;
  sim.materials = MaterialTable({ball()}, {});
  sim.walls.push_back(Wall{"plate", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, motion});
  sim.dt = 4e-5;  // 0.1 of eq. 2.48's 4.1e-4 s
  return sim;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(StartChecks, NoneForASphereRestingOnAStillPlate) {
  Simulation sim = plate_scene();
  sim.particles.add(0, Vec3(0, 0, kRadius * 0.999), kRadius, 2000, 0);
  EXPECT_TRUE(StartChecks(sim).suspects().empty());
}

TEST(StartChecks, OverlapWithAWallAtStepZero) {
  Simulation sim = plate_scene();
  sim.particles.add(0, Vec3(0, 0, 0.2 * kRadius), kRadius, 2000, 0);  // 80 % into the plate
  const StartChecks c(sim);
  ASSERT_EQ(c.suspects().size(), 1u);
  EXPECT_TRUE(has(c.suspects()[0].text, "1 particles overlap walls at step 0")) << c.suspects()[0].text;
  EXPECT_TRUE(has(c.suspects()[0].text, "particle 0 and wall plate")) << c.suspects()[0].text;
  EXPECT_NEAR(c.suspects()[0].score, 0.8 / 0.1, 1e-9) << "the overlap over 0.2 x max_overlap";
}

TEST(StartChecks, GenerationBoxCrossedByAWallComesFirst) {
  Simulation sim = plate_scene();
  sim.particles.add(0, Vec3(0, 0, 0.5 * kRadius), kRadius, 2000, 0);
  GenerationSpec g;
  g.box_min = Vec3(-0.1, -0.1, -0.1);
  g.box_max = Vec3(0.1, 0.1, 0.1);
  const StartChecks c(sim, &g);
  ASSERT_EQ(c.suspects().size(), 1u) << "the box and the overlaps it causes are one finding";
  EXPECT_EQ(c.suspects()[0].text.rfind("the generation box [-0.1, -0.1, -0.1] to [0.1, 0.1, 0.1] m is not inside the walls: wall \"plate\" crosses it", 0),
            0u)
      << c.suspects()[0].text;
  EXPECT_TRUE(has(c.suspects()[0].text, "1 particles overlap walls")) << c.suspects()[0].text;
  // A box above the plate, the floor on its face: nothing crosses it.
  g.box_min = Vec3(-0.1, -0.1, 0);
  sim.particles = Particles{};
  sim.particles.add(0, Vec3(0, 0, 0.05), kRadius, 2000, 0);
  EXPECT_TRUE(StartChecks(sim, &g).suspects().empty());
}

TEST(StartChecks, FastWallRanksAboveAnInitialOverlapAndTheBlowUpListsBoth) {
  WallMotion shake;
  shake.direction = Vec3::UnitZ();
  shake.frequency = 20;
  shake.amplitude = 2;  // meant as 2 mm: 251 m/s peak
  Simulation sim = plate_scene(shake);
  sim.particles.add(0, Vec3(0, 0, 0.5), kRadius, 2000, 0);
  sim.particles.add(1, Vec3(1.4 * kRadius, 0, 0.5), kRadius, 2000, 0);  // 60 % overlap
  const StartChecks c(sim);
  ASSERT_EQ(c.suspects().size(), 2u);
  EXPECT_TRUE(has(c.suspects()[0].text, "wall \"plate\" moves faster than the particles can follow")) << c.suspects()[0].text;
  EXPECT_TRUE(has(c.suspects()[0].text, "vibration amplitude in mm? (m expected)")) << c.suspects()[0].text;
  EXPECT_TRUE(has(c.suspects()[1].text, "initial overlap between particles: 1 pairs")) << c.suspects()[1].text;
  EXPECT_TRUE(has(c.suspects()[1].text, "the largest 60 %")) << c.suspects()[1].text;
  try {
    c.rethrow(PhysicsError("overlap of 70 % at step 3", "lower the time step (frac)"));
    FAIL() << "rethrow returned";
  } catch (const PhysicsError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("overlap of 70 % at step 3. Likely causes, most likely first (checked at step 0): (1) wall \"plate\" moves faster", 0), 0u) << m;
    EXPECT_TRUE(has(m, "; (2) initial overlap between particles")) << m;
    EXPECT_TRUE(has(m, "; (3) otherwise the time step or the stiffness: lower the time step (frac)")) << m;
    EXPECT_EQ(e.advice, "lower the time step (frac)");
  }
  // A plate shaking at 3 g and 20 Hz (1.9 mm) is no suspect.
  sim.walls[0].motion.amplitude = 3 * 9.81 / std::pow(2 * M_PI * 20, 2);
  sim.particles = Particles{};
  sim.particles.add(0, Vec3(0, 0, 0.5), kRadius, 2000, 0);
  EXPECT_TRUE(StartChecks(sim).suspects().empty());
}

// Bonds that hold far beyond a diameter (a tensile strength far above the forces carried: Liu's
// bond breaks at F / kn, eq. P11) widen the neighbour search to their reach: a warning on cost, not
// a suspect of a failure. A strength of 1 N breaks 1e-5 m apart, 1e9 N 1e4 m apart.
TEST(StartChecks, BondsReachingBeyondADiameterWarn) {
  for (const double strength : {1.0, 1e9}) {
    Simulation sim;
    Material m = ball();
    m.law = NormalLaw::Liu;
    m.tensile_strength = strength;
    sim.materials = MaterialTable({m}, {});
    sim.dt = 4e-5;
    sim.particles.add(0, Vec3(0, 0, 0), kRadius, 2000, 0);
    sim.particles.add(1, Vec3(1.99 * kRadius, 0, 0), kRadius, 2000, 0);
    ASSERT_EQ(sim.bond_present_contacts(false), 1u);
    ASSERT_TRUE(sim.has_bonds());
    const StartChecks c(sim);
    EXPECT_TRUE(c.suspects().empty()) << "a bond's reach causes no failure";
    if (strength < 1e3) {
      EXPECT_TRUE(c.slow().empty()) << c.slow()[0];
    } else {
      ASSERT_EQ(c.slow().size(), 1u);
      EXPECT_TRUE(has(c.slow()[0], "bonds hold until their particles are 10000 m apart")) << c.slow()[0];
      EXPECT_TRUE(has(c.slow()[0], "more than the largest diameter (0.02 m)")) << c.slow()[0];
    }
  }
}

TEST(StartChecks, NoSuspectsLeaveTheErrorAsItIs) {
  Simulation sim = plate_scene();
  sim.particles.add(0, Vec3(0, 0, 0.5), kRadius, 2000, 0);
  try {
    StartChecks(sim).guard([] { throw PhysicsError("facts", "advice"); });
    FAIL();
  } catch (const PhysicsError& e) {
    EXPECT_STREQ(e.what(), "facts: advice");
  }
}

}  // namespace
}  // namespace dem
