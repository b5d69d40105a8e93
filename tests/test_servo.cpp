// The servo law (control/servo.hpp) against the analytic answer on a plant without chaos: a lid held
// by n linear springs on a bed whose surface rises towards it at a steady rate r (as a side wall
// squeezing the sample pushes it up). Proportional control must lag by exactly the error that
// makes the lid retreat at r; PI control must bring that error to zero. The chaotic squeeze of
// tests/servo_stage.sh shows the same on real particles, but one run of it cannot tell the two
// apart reliably (force chains buckle at random); this test can.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/servo.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

constexpr double kArea = 4e-4, kTarget = 1000, kStiffness = 5e4, kRate = 1e-3, kDt = 1e-5, kGain = 0.2;
constexpr int kContacts = 10;

ServoGroup lid(double max_speed, double integral_time) {
  ServoGroup g;
  g.elements = {0};
  g.inward = Vec3(0, 0, -1);
  g.area = kArea;
  g.target = kTarget;
  g.max_speed = max_speed;
  g.gain = kGain;
  g.integral_time = integral_time;
  return g;
}

// Runs the lid for `steps`: the compression s of the springs grows by (v + r) dt per step, v the
// lid's inward speed; the lid feels n k s. Returns the mean stress over the second half and
// checks every speed against the limit.
double mean_stress_second_half(ServoGroup& g, int steps) {
  double compression = kTarget * kArea / (kContacts * kStiffness);  // at the target to begin with
  std::vector<WallLoad> loads(1);
  loads[0].contacts = kContacts;
  double sum = 0;
  for (int s = 0; s < steps; ++s) {
    loads[0].force = -g.inward * (kContacts * kStiffness * compression);  // the bed pushes the lid out
    if (s >= steps / 2) sum += g.stress(loads);
    const double v = g.speed(loads, kDt, kStiffness, 0.0);  // no dashpots in this plant: c_max = 0
    EXPECT_LE(std::abs(v), g.max_speed);
    compression += (v + kRate) * kDt;
  }
  return sum / (steps - steps / 2);
}

TEST(Servo, ProportionalLagsByRateOverGainAndIntegralActionRemovesIt) {
  // Steady state of the proportional servo: the lid must retreat at r, so gain u = -r with
  // u = (target - stress) area / (n k dt): stress - target = r n k dt / (gain area) = 62.5 Pa.
  const double lag = kRate * kContacts * kStiffness * kDt / (kGain * kArea);
  ServoGroup proportional = lid(0.2, 0);
  const double p = mean_stress_second_half(proportional, 20000);
  // The error decays by (1 - gain) per step: after 10,000 steps nothing of the start is left;
  // 1e-9 relative allows the round-off of 10,000 sums.
  EXPECT_NEAR(p - kTarget, lag, 1e-9 * kTarget);
  // PI (T_i = 300 steps): the integral takes over the speed r; after 30 T_i the mean error of the
  // second half is a vanishing part of the lag (1e-3 of it asked).
  ServoGroup pi_lid = lid(0.2, 0.003);
  const double pi = mean_stress_second_half(pi_lid, 20000);
  EXPECT_LT(std::abs(pi - kTarget), 1e-3 * lag) << "PI mean " << pi << " Pa";
}

TEST(Servo, IntegralActionStaysWithinTheSpeedLimit) {
  // A rate beyond max_speed cannot be followed: the integral must stop at the limit (anti-windup),
  // not grow without bound.
  ServoGroup g = lid(1e-4, 0.003);  // max_speed below kRate
  mean_stress_second_half(g, 20000);  // checks every speed against the limit
  EXPECT_LE(std::abs(g.integral), g.max_speed);
}

}  // namespace
}  // namespace dem
