// What issue 33's cases need of a stage, checked against closed forms: the bond action's gap
// tolerance (a touching pair or lattice bonds), [[stage.set_velocity]] (a free particle given v0
// follows x0 + v0 t + g t^2 / 2) and [[stage.prescribe]] (a group moves at exactly its velocity,
// whatever the forces; the force the rest exerts on it is reported; it survives a checkpoint).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "contact/normal_laws.hpp"
#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "run/particle_groups.hpp"
#include "same_bits.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

constexpr double kRadius = 1e-3;  // [m]
constexpr double kDensity = 2500;
constexpr double kKn = 1e5;       // [N/m]
constexpr double kStrength = 1.0; // F [N]

Material material(NormalLaw law, double epsilon, const char* name = "m") {
  Material m;
  m.name = name;
  m.density = kDensity;
  m.kn = kKn;
  m.kt = kKn;
  m.friction_angle = 30;
  m.restitution = 1;  // no damping: forces are the elastic laws alone
  m.restitution_t = 1;
  m.law = law;
  m.tensile_strength = kStrength;
  m.cohesion = 0.5;
  m.epsilon = epsilon;
  return m;
}

Simulation empty_sim(const std::vector<Material>& mats) {
  Simulation sim;
  sim.materials = MaterialTable(mats, {});
  sim.params.gravity = Vec3::Zero();
  return sim;
}

std::size_t bonded_count(const Simulation& sim) {
  std::size_t n = 0;
  for (std::uint8_t b : sim.pair_contacts().bonded) n += b;
  for (std::uint8_t b : sim.wall_contacts().bonded) n += b;
  return n;
}

// ---------------------------------------------------------------------------------------------
// The bond action's gap: a pair at exactly zero overlap is no contact (the force loop's test is
// overlap > 0), so `bond` with gap 0 leaves it; with the default gap (1e-6 of the smaller radius)
// it bonds; a pair apart by more than the gap does not.

TEST(BondGap, TouchingPairBondsWithinTheGapOnly) {
  auto pair_at = [](double gap_over_radius) {
    Simulation sim = empty_sim({material(NormalLaw::Liu, 1e-4)});
    sim.particles.add(0, Vec3(0, 0, 0), kRadius, kDensity, 0);
    sim.particles.add(1, Vec3(2 * kRadius + gap_over_radius * kRadius, 0, 0), kRadius, kDensity, 0);
    sim.dt = 0.1 * sim.critical_time_step();
    return sim;
  };
  Simulation exact = pair_at(0);  // 2a = 0.002 exactly: overlap 0
  EXPECT_EQ(exact.bond_present_contacts(false, 0), 0u) << "overlap 0 is no contact for the force loop";
  EXPECT_EQ(exact.bond_present_contacts(false, kBondTouchTolerance), 1u);
  Simulation near = pair_at(0.5e-6);
  EXPECT_EQ(near.bond_present_contacts(false, 1e-6), 1u);
  Simulation apart = pair_at(2e-6);
  EXPECT_EQ(apart.bond_present_contacts(false, 1e-6), 0u) << "a gap of twice the tolerance is a gap";
  EXPECT_EQ(apart.bond_present_contacts(false, 1e-5), 1u) << "a wider tolerance takes it";
}

// A simple cubic lattice of touching spheres (pitch 2a, positions offset so that the gaps come out
// a few ulps either side of zero) on a floor it touches: with the default gap every one of the
// 3 x (3 x 3 x 2) = 54 neighbour pairs and 9 floor contacts bonds. With mendes at eps = 0.5 (no
// tension: the bond breaks once the particles separate) the lattice left at rest keeps all 63
// for 500 steps: gaps of round-off are no separation.
TEST(BondGap, TouchingLatticeOnAFloorBondsAndHolds) {
  auto lattice = []() {
    Simulation sim = empty_sim({material(NormalLaw::Mendes, 0.5)});
    sim.walls.push_back(Wall{"floor", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
    const Vec3 origin(0.1234567, -0.0765431, kRadius);
    Index id = 0;
    for (int iz = 0; iz < 3; ++iz)
      for (int iy = 0; iy < 3; ++iy)
        for (int ix = 0; ix < 3; ++ix) sim.particles.add(id++, origin + 2 * kRadius * Vec3(ix, iy, iz), kRadius, kDensity, 0);
    sim.dt = 0.1 * sim.critical_time_step();
    return sim;
  };
  Simulation none = lattice();
  EXPECT_LT(none.bond_present_contacts(true, 0), 63u) << "at gap 0 the exactly touching ones are missed";
  Simulation sim = lattice();
  ASSERT_EQ(sim.bond_present_contacts(true, kBondTouchTolerance), 63u);
  for (int s = 0; s < 500; ++s) sim.advance();
  EXPECT_EQ(bonded_count(sim), 63u);
}

// ---------------------------------------------------------------------------------------------
// [[stage.set_velocity]]: groups by material, id range and region; v (and w) set once.

TEST(SetVelocity, GroupsByMaterialIdsAndRegion) {
  Simulation sim = empty_sim({material(NormalLaw::Cundall, 1e-4, "A"), material(NormalLaw::Cundall, 1e-4, "B")});
  for (int k = 0; k < 10; ++k) sim.particles.add(k, Vec3(0.01 * k, 0, 0), kRadius, kDensity, k % 2);
  ParticleGroupSpec g;
  g.material = 1;
  EXPECT_EQ(select_group(sim, g), (std::vector<std::size_t>{1, 3, 5, 7, 9}));
  g.by_ids = true, g.id_first = 4, g.id_last = 8;
  EXPECT_EQ(select_group(sim, g), (std::vector<std::size_t>{5, 7}));
  Region box;
  box.min = Vec3(0.055, -1, -1), box.max = Vec3(1, 1, 1);
  g.region = box;
  EXPECT_EQ(select_group(sim, g), (std::vector<std::size_t>{7}));
  g.inside = false;
  EXPECT_EQ(select_group(sim, g), (std::vector<std::size_t>{5}));
  ParticleGroupSpec ids;
  ids.by_ids = true, ids.id_first = 3, ids.id_last = 3;
  VelocitySpec v{ids, Vec3(1, 2, 3), std::nullopt};
  sim.particles.w[3] = Vec3(0, 0, 7);
  EXPECT_EQ(set_group_velocity(sim, v), 1u);
  EXPECT_EQ(sim.particles.v[3], Vec3(1, 2, 3));
  EXPECT_EQ(sim.particles.w[3], Vec3(0, 0, 7)) << "no angular_velocity given: the spin is kept";
  EXPECT_EQ(sim.particles.v[2], Vec3::Zero());
  v.angular_velocity = Vec3(4, 5, 6);
  set_group_velocity(sim, v);
  EXPECT_EQ(sim.particles.w[3], Vec3(4, 5, 6));
}

// A free particle given v0 under gravity: x(t) = x0 + v0 t + g t^2 / 2. The leapfrog (v at half
// steps, v0 taken as v^{-1/2}) gives x_n = x0 + v0 t + g dt^2 n (n + 1) / 2 exactly, that is
// g t dt / 2 off the continuous closed form: checked against the continuous form within |g| t dt
// and against the discrete form to 1e-12 relative. Its spin stays as given (no torque).
TEST(SetVelocity, FreeParticleFollowsTheBallisticClosedForm) {
  Simulation sim = empty_sim({material(NormalLaw::Cundall, 1e-4)});
  sim.params.gravity = Vec3(0, 0, -9.81);
  sim.particles.add(0, Vec3(0, 0, 0), kRadius, kDensity, 0);
  sim.particles.add(1, Vec3(1, 0, 0), kRadius, kDensity, 0);  // far away, left at rest
  sim.dt = 1e-4;
  ParticleGroupSpec g;
  g.by_ids = true;
  const Vec3 v0(1.5, -0.5, 5), w0(0, 10, 0);
  ASSERT_EQ(set_group_velocity(sim, VelocitySpec{g, v0, w0}), 1u);
  const Vec3 x0 = sim.particles.x[0], g_vec = sim.params.gravity;
  const int n = 5000;
  for (int s = 0; s < n; ++s) sim.advance();
  const double t = n * sim.dt;
  const Vec3 continuous = x0 + v0 * t + 0.5 * g_vec * t * t;
  const Vec3 discrete = x0 + v0 * t + g_vec * (sim.dt * sim.dt * n * (n + 1) / 2.0);
  EXPECT_LE((sim.particles.x[0] - continuous).norm(), g_vec.norm() * t * sim.dt);
  EXPECT_LE((sim.particles.x[0] - discrete).norm(), 1e-12 * continuous.norm());
  EXPECT_EQ(sim.particles.w[0], w0);
  EXPECT_EQ(sim.particles.v[1].x(), 0.0) << "the other particle only falls";
}

// ---------------------------------------------------------------------------------------------
// [[stage.prescribe]]: the group moves at exactly its velocity whatever the forces.

// A prescribed sphere at 0.2 m/s under gravity ploughs through a free one in its way: its velocity
// and spin stay the given bits, its position is x0 + n v dt to round-off (n additions: 1e-12
// relative); the free sphere is pushed (it gains speed along x).
TEST(Prescribe, GroupMovesAtExactlyItsVelocity) {
  Simulation sim = empty_sim({material(NormalLaw::Cundall, 1e-4)});
  sim.params.gravity = Vec3(0, 0, -9.81);
  sim.particles.add(0, Vec3(0, 0, 0), kRadius, kDensity, 0);
  sim.particles.add(1, Vec3(2.1 * kRadius, 0.2 * kRadius, 0), kRadius, kDensity, 0);
  sim.dt = 0.1 * sim.critical_time_step();
  ParticleGroupSpec g;
  g.by_ids = true;
  const Vec3 v(0.2, 0, 0), w(0, 0, 3);
  ASSERT_EQ(start_prescribed(sim, VelocitySpec{g, v, w}), 1u);
  EXPECT_EQ(sim.particles.fixed[0], kPrescribed);
  const Vec3 x0 = sim.particles.x[0];
  const int n = 2000;
  double largest_force = 0;
  for (int s = 0; s < n; ++s) {
    sim.advance();
    largest_force = std::max(largest_force, force_on_prescribed(sim).norm());
  }
  EXPECT_TRUE(same_bits(std::vector<Vec3>{sim.particles.v[0], sim.particles.w[0]}, std::vector<Vec3>{v, w}));
  EXPECT_LE((sim.particles.x[0] - (x0 + n * sim.dt * v)).norm(), 1e-12 * (n * sim.dt * v).norm());
  EXPECT_GT(sim.particles.v[1].x(), 0.1) << "the free sphere was pushed";
  EXPECT_GT(largest_force, 0.0) << "the contact pushed back on the prescribed sphere";
  EXPECT_EQ(end_prescribed(sim), 1u);
  EXPECT_EQ(sim.particles.fixed[0], kFree);
  sim.advance();
  EXPECT_LT(sim.particles.v[0].z(), 0.0) << "free again, it falls";
}

// The pull test of issue 33: sphere 0 held, sphere 1 prescribed at 2 mm/s away from it, bonded at
// exactly zero overlap (the default gap). liu: the force on the prescribed sphere is the bond's
// tension k_n s (pulling it back, -x) to 1e-9 F, until k_n s exceeds F, where the bond breaks.
// mendes at eps = 0.5 (no tension): the bond breaks in the first step whose gap exceeds the
// tolerance 2e-6 R*; pushed back by a second prescription, the pair touches unbonded.
TEST(Prescribe, PullsABondedPairApart) {
  for (NormalLaw law : {NormalLaw::Liu, NormalLaw::Mendes}) {
    Simulation sim = empty_sim({material(law, 0.5)});
    sim.particles.add(0, Vec3(0, 0, 0), kRadius, kDensity, 0);
    sim.particles.add(1, Vec3(2 * kRadius, 0, 0), kRadius, kDensity, 0);
    sim.dt = 0.1 * sim.critical_time_step();
    ASSERT_EQ(sim.bond_present_contacts(false, kBondTouchTolerance), 1u);
    sim.particles.fixed[0] = kHeld;
    ParticleGroupSpec one;
    one.by_ids = true, one.id_first = one.id_last = 1;
    const double rate = 2e-3;
    start_prescribed(sim, VelocitySpec{one, Vec3(rate, 0, 0), std::nullopt});
    double s_break = -1;
    for (int k = 0; k < 100000 && s_break < 0; ++k) {
      const double s = (sim.particles.x[1] - sim.particles.x[0]).norm() - 2 * kRadius;  // the gap this step sees
      sim.advance();
      if (bonded_count(sim) == 0) s_break = s;
      else if (law == NormalLaw::Liu && s > 0) EXPECT_NEAR(force_on_prescribed(sim).x(), -kKn * s, 1e-9 * kStrength) << "s = " << s;
    }
    const double ds = rate * sim.dt;
    if (law == NormalLaw::Liu) {
      EXPECT_GT(s_break, kStrength / kKn);
      EXPECT_LE(s_break, kStrength / kKn + ds * (1 + 1e-6));
    } else {
      const double tolerance = kBondTouchTolerance * 2 * (kRadius / 2);
      EXPECT_GT(s_break, tolerance) << "held while touching";
      EXPECT_LE(s_break, tolerance + ds * (1 + 1e-6)) << "broken in the first step apart";
    }
    EXPECT_EQ(force_on_prescribed(sim).norm(), 0.0) << "no force once broken";
    // Push back into contact: an ordinary, unbonded contact.
    end_prescribed(sim);
    start_prescribed(sim, VelocitySpec{one, Vec3(-rate, 0, 0), std::nullopt});
    bool touched = false;
    for (int k = 0; k < 200000 && !touched; ++k) {
      sim.advance();
      touched = sim.pair_contacts().size() > 0 && sim.pair_contacts().force(0).norm() > 0;
    }
    ASSERT_TRUE(touched);
    EXPECT_EQ(bonded_count(sim), 0u) << "a broken bond never re-forms";
  }
}

// The energy check (simulation.max_energy_gain) counts the work the prescription does: a prescribed
// sphere at 1 m/s knocking a free one away (which then carries up to 4x the prescribed sphere's
// kinetic energy) is no energy created. Without that term this run stops as unstable.
TEST(Prescribe, EnergyCheckCountsThePrescribedWork) {
  Material m = material(NormalLaw::Cundall, 1e-4);
  m.restitution = 0.9;
  Simulation sim = empty_sim({m});
  sim.particles.add(0, Vec3(0, 0, 0), kRadius, kDensity, 0);
  sim.particles.add(1, Vec3(2.05 * kRadius, 0, 0), kRadius, kDensity, 0);
  sim.dt = 0.05 * sim.critical_time_step();
  ParticleGroupSpec g;
  g.by_ids = true;
  start_prescribed(sim, VelocitySpec{g, Vec3(1, 0, 0), std::nullopt});
  ASSERT_GT(sim.params.max_energy_gain, 0);
  EXPECT_NO_THROW(for (int s = 0; s < 3000; ++s) sim.advance());
  EXPECT_GT(sim.particles.v[1].x(), 1.5) << "knocked away at about twice the prescribed speed";
}

// A prescribed group survives a checkpoint: written mid-prescription and read back, the run goes
// on to the bits of the uninterrupted one.
TEST(Prescribe, SurvivesACheckpointToTheBit) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dem_prescribe_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Simulation sim = empty_sim({material(NormalLaw::Liu, 1e-4)});
  sim.params.gravity = Vec3(0, 0, -9.81);
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}, {}});
  Index id = 0;
  for (int ix = 0; ix < 4; ++ix)
    for (int iz = 0; iz < 3; ++iz) sim.particles.add(id++, Vec3(1.98 * kRadius * ix, 0, kRadius * (0.99 + 1.98 * iz)), kRadius, kDensity, 0);
  sim.dt = 0.1 * sim.critical_time_step();
  sim.bond_present_contacts(true, kBondTouchTolerance);
  ParticleGroupSpec top;
  top.by_ids = true, top.id_first = 2, top.id_last = 2;
  start_prescribed(sim, VelocitySpec{top, Vec3(0.01, 0, 0.005), Vec3(0, 1, 0)});
  for (int s = 0; s < 300; ++s) sim.advance();
  CheckpointMeta meta;
  meta.writer = "test";
  const std::string path = (dir / "mid.h5").string();
  write_checkpoint(path, sim, meta);
  Simulation resumed;
  CheckpointMeta read_meta;
  read_checkpoint(path, resumed, read_meta);
  EXPECT_EQ(resumed.particles.fixed[2], kPrescribed);
  for (int s = 0; s < 300; ++s) sim.advance(), resumed.advance();
  EXPECT_TRUE(same_bits(sim.particles.x, resumed.particles.x));
  EXPECT_TRUE(same_bits(sim.particles.v, resumed.particles.v));
  EXPECT_EQ(resumed.particles.v[2], Vec3(0.01, 0, 0.005));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dem
