// Prescribed wall motion (SPEC §3): translation, time tables, vibration, rotation and their
// composition, and the wall velocity entering the contact law (eq. 2.18). Expected answers: the
// closed-form rigid motion, the lift-off condition of a sphere on a vibrating plate (Γ > 1, at
// sin(ωt) = 1/Γ), and a sphere carried round by a rotating drum.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/simulation.hpp"
#include "walls/wall.hpp"

namespace dem {
namespace {

constexpr double kPi = std::numbers::pi;

WallMotion composite() {
  WallMotion m;
  m.velocity = Vec3(0.01, 0, 0);
  m.table_time = {0, 0.5, 1.5};
  m.table_offset = {Vec3::Zero(), Vec3(0, 0.02, 0), Vec3(0, 0.02, -0.01)};
  m.direction = Vec3(0, 0, 1);
  m.frequency = 3;
  m.amplitude = 0.002;
  m.centre = Vec3(0.1, 0.2, 0.3);
  m.axis = Vec3(1, 2, 2).normalized();
  m.angular_speed = 4.0;
  m.t0 = 0.25;
  return m;
}

// Positions follow x(t) = c + d(s) + R(ω s)(x0 - c), written out here with Rodrigues' formula;
// velocities equal the time derivative of positions (central difference, h = 1e-6 s: error
// ~h^2 |x'''| ~ 1e-12, so 1e-7 relative is ample while a wrong lever arm is off by O(1)).
TEST(WallMotion, CompositeMotionIsTheRigidMotionAndItsDerivative) {
  const WallMotion m = composite();
  const Vec3 x0(0.3, -0.1, 0.5);
  for (double t : {0.25, 0.4, 0.9, 1.3, 2.5}) {
    const double s = t - m.t0;
    Vec3 table = Vec3::Zero();
    if (s >= 1.5) table = Vec3(0, 0.02, -0.01);
    else if (s >= 0.5) table = Vec3(0, 0.02, -0.01 * (s - 0.5));
    else table = Vec3(0, 0.02 * s / 0.5, 0);
    const Vec3 d = m.velocity * s + table + m.direction * (m.amplitude * std::sin(2 * kPi * m.frequency * s));
    const Vec3 r = x0 - m.centre, k = m.axis;
    const double th = m.angular_speed * s;
    const Vec3 rot = r * std::cos(th) + k.cross(r) * std::sin(th) + k * k.dot(r) * (1 - std::cos(th));
    EXPECT_LT((m.place(x0, t) - (m.centre + d + rot)).norm(), 1e-15) << "t = " << t;
    if (std::abs(s) < 1e-3 || std::abs(s - 0.5) < 1e-3 || std::abs(s - 1.5) < 1e-3) continue;  // table corners: no derivative
    Wall w{"w", 0, {x0, x0 + Vec3(0.01, 0, 0), x0 + Vec3(0, 0.01, 0)}, m};
    WallGeometry g;
    place_wall(w, t, 0, g);
    const double h = 1e-6;
    const Vec3 numeric = (m.place(x0, t + h) - m.place(x0, t - h)) / (2 * h);
    EXPECT_LT((g.velocity_of(m.place(x0, t)) - numeric).norm(), 1e-7 * numeric.norm()) << "t = " << t;
  }
}

// A sphere resting on a plate that vibrates vertically with peak acceleration Γ g stays on it for
// Γ < 1 and leaves it for Γ > 1 when the plate's downward acceleration first exceeds g, at phase
// sin(ω t) = 1/Γ after the lowest point (the contact force m (g + a_plate) reaches zero there;
// the contact is 200 times faster than the plate, so it follows quasi-statically). Tolerance 1.5
// degrees of phase: the dashpot and the contact's own compliance delay it by less.
TEST(WallMotion, SphereOnVibratingPlateLeavesExactlyWhenGammaExceedsOne) {
  for (double gamma : {0.8, 0.95, 1.2, 2.0}) {
    Simulation sim;
    Material m;
    m.name = "glass";
    m.kn = m.kt = 1e6;
    sim.materials = MaterialTable({m}, {});
    const double f = 20, om = 2 * kPi * f, A = gamma * 9.81 / (om * om);
    WallMotion vib;
    vib.frequency = f;
    vib.amplitude = A;
    vib.t0 = 0.25 / f;  // the plate starts at its lowest point, at rest
    // Plate z = A sin(ω (t - t0)): at t = 0 at its lowest point z = -A.
    sim.walls.push_back(Wall{"plate", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, vib});
    const double a = 0.005;
    sim.particles.add(0, Vec3(0, 0, -A + a - sphere_mass(2500, a) * 9.81 / m.kn), a, 2500, 0);  // resting overlap m g / k
    sim.dt = 2e-6;
    double liftoff_phase = -1;
    const int steps = static_cast<int>(3 / f / sim.dt);  // three cycles
    for (int s = 0; s < steps && liftoff_phase < 0; ++s) {
      sim.advance();
      if (sim.wall_contacts().size() == 0 || sim.wall_contacts().force(0).z() <= 0)
        liftoff_phase = std::fmod(om * (sim.time - vib.t0) + 2 * kPi, 2 * kPi);  // plate z = A sin(phase)
    }
    if (gamma < 1) {
      EXPECT_LT(liftoff_phase, 0) << "Γ = " << gamma << ": the sphere must stay on the plate";
    } else {
      // The plate's acceleration is -A ω² sin(phase): downward beyond g once sin(phase) > 1/Γ,
      // first on its way up from the rest position (phase 0) to the top (π/2).
      const double want = std::asin(1 / gamma);
      std::printf("  Γ = %.2f: lift-off at phase %.2f deg, predicted %.2f deg\n", gamma, liftoff_phase * 180 / kPi, want * 180 / kPi);
      ASSERT_GE(liftoff_phase, 0) << "Γ = " << gamma << ": the sphere must leave the plate";
      EXPECT_NEAR(liftoff_phase, want, 1.5 * kPi / 180) << "Γ = " << gamma;
    }
  }
}

// A sphere riding on the inner surface of a drum (64 facets, turning at 120 rpm, no gravity) in
// the co-rotating state is carried round by the wall: the wall's velocity at the contact point
// (eq. 2.18) matches the sphere's, so no tangential force arises and the sphere keeps pace with
// the drum while crossing 64 facet edges. Without the rotation in the wall velocity the friction
// would brake it within a fraction of a turn. Tolerance: 0.5 degree after one turn.
TEST(WallMotion, SphereCoRotatesWithARotatingDrum) {
  const int segments = 64;
  const double R = 0.1, L = 0.05, om = 120 * 2 * kPi / 60;
  Simulation sim;
  Material m;
  m.name = "steel";
  m.kn = m.kt = 1e6;
  m.friction_angle = 30;
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3::Zero();
  auto rim = [&](int s, double y) {
    const double t = 2 * kPi * s / segments;
    return Vec3(R * std::cos(t), y, R * std::sin(t));
  };
  WallMotion spin;
  spin.axis = Vec3(0, -1, 0);  // from +x towards +z: the angle t increases
  spin.angular_speed = om;
  for (int s = 0; s < segments; ++s)
    sim.walls.push_back(Wall{"drum." + std::to_string(s), 0, {rim(s, 0), rim(s + 1, 0), rim(s + 1, L), rim(s, L)}, spin});
  const double a = 0.005;
  // Centre on the facet's mid-line, pressed by the centripetal force m ω² r: overlap m ω² r / k.
  const double apothem = R * std::cos(kPi / segments);
  const double mass = sphere_mass(2500, a);
  double r = apothem - a;
  r += mass * om * om * r / m.kn;
  const double t0 = kPi / segments;  // angle of the first facet's mid-line
  sim.particles.add(0, Vec3(r * std::cos(t0), L / 2, r * std::sin(t0)), a, 2500, 0);
  sim.particles.v[0] = spin.angular_speed * spin.axis.cross(sim.particles.x[0]);
  sim.particles.w[0] = spin.angular_speed * spin.axis;
  sim.dt = 2e-6;  // a twentieth of the critical step
  const int steps = static_cast<int>(std::round(2 * kPi / om / sim.dt));  // one turn
  int lost = 0;
  for (int s = 0; s < steps; ++s) {
    sim.advance();
    lost += sim.wall_contacts().size() == 0;
  }
  const Vec3& x = sim.particles.x[0];
  const double angle = std::atan2(x.z(), x.x()), drum = std::fmod(t0 + om * sim.time, 2 * kPi);
  double lag = angle - (drum > kPi ? drum - 2 * kPi : drum);
  std::printf("  drum: after %.3f s (%.2f turns) the sphere is %.4f deg from the co-rotating point, %d steps without contact\n",
              sim.time, om * sim.time / (2 * kPi), lag * 180 / kPi, lost);
  EXPECT_LT(std::abs(lag), 0.5 * kPi / 180);
  EXPECT_EQ(lost, 0);
}

}  // namespace
}  // namespace dem
