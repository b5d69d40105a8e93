// The energy ledger (sim/energy_ledger.hpp, docs/physics.md eq. P29-P39) against closed forms:
// the dashpot's loss in a binary collision, Coulomb friction's in a sphere sliding into rolling,
// a bond's energy when it breaks; each step's contact work against its definition from the step's
// forces and velocities; and the whole balance in bonded blocks that collide and a sphere on a
// tilting wall, with the same bits on any thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "../bench/binary_collision.hpp"
#include "core/error.hpp"
#include "run/energy_log.hpp"
#include "simd/exact_sum.hpp"
#include "simd/simd.hpp"
#include "sim/health.hpp"
#include "sim/simulation.hpp"

namespace dem {
namespace {

// --- A damped binary collision: the dashpot takes ½ m* v² (1 - e²). ---------------------------
// Also with the explicit dashpot (docs/contact-laws.md eq. D7), whose restitution is first order in
// the step: the ledger must take the loss the run shows, whichever form the dashpot has.
TEST(Energy, DashpotTakesHalfMStarVSquaredTimesOneMinusESquaredInABinaryCollision) {
  using namespace collision;
  for (bool explicit_form : {false, true})
  for (bool wall : {false, true})
    for (double eta : {0.3, 0.7}) {
      Shot s;
      s.wall = wall;
      s.eta = eta;
      s.explicit_dashpot = explicit_form;
      const double m = effective_mass(wall);
      s.t_ref = linear_closed_form(s.kn, m, eta, s.v).duration;
      s.ledger = true;
      const Result r = collide(s);
      const double e0 = 0.5 * m * s.v * s.v;
      const double closed = e0 * (1 - eta * eta);
      // tests/test_restitution.cpp: at 50 steps per contact the restitution is within 1 % of eta,
      // so the loss ½ m* v² (1 - e²) is within ½ m* v² (e² - (0.99 e)²) ≈ 0.02 e² ½ m* v² of it.
      if (!explicit_form) EXPECT_NEAR(r.ledger.totals.damping_normal, closed, 0.02 * eta * eta * e0) << (wall ? "wall " : "pair ") << eta;
      // Against the loss the run itself shows (the restitution it reached): the ledger takes the
      // dashpot's work as the integrator applies it, so only the elastic energy at the touch and
      // the release is off, O((ω Δt)²) = (π/50)² = 0.4 % of ½ m* v² at most.
      const double shown = e0 * (1 - r.restitution * r.restitution);
      const std::string what = std::string(explicit_form ? "explicit, " : "") + (wall ? "wall " : "pair ") + std::to_string(eta);
      EXPECT_NEAR(r.ledger.totals.damping_normal, shown, 4e-3 * e0) << what;
      EXPECT_LT(std::abs(r.ledger.error()), 4e-3 * e0) << what;
      EXPECT_EQ(r.ledger.totals.global_damping, 0.0);
    }
}

// A material of the default (linear) law: density [kg/m^3], kn = kt [N/m], friction angle [deg],
// restitution.
Material linear_material(const char* name, double density, double k, double friction_angle, double restitution) {
  Material m;
  m.name = name;
  m.density = density;
  m.kn = m.kt = k;
  m.friction_angle = friction_angle;
  m.restitution = restitution;
  return m;
}

// --- A sphere sliding on a plane until it rolls: friction takes m v0² / 7. ----------------------
// Closed form: sliding at v0 without spin, the slip speed v - a ω falls at (1 + 5/2) μ g, so the
// sphere slides a slip distance v0² / (7 μ g), and friction takes μ m g times it = m v0² / 7 (the
// kinetic energy drops from ½ m v0² to ½ m (5/7 v0)² (1 + 2/5) = 5/7 of it).
TEST(Energy, FrictionTakesMuMGTimesTheSlipDistanceOfASphereSlidingIntoRolling) {
  Simulation sim;
  Material m = linear_material("steel", 7800, 1e6, 20, 0.5);
  m.restitution_t = 1;
  sim.materials = MaterialTable({m}, {});
  const double a = 0.005, mu = std::tan(20 * std::numbers::pi / 180), g = 9.81, v0 = 0.5;
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-5, -5, 0), Vec3(5, -5, 0), Vec3(5, 5, 0), Vec3(-5, 5, 0)}, {}});
  sim.particles.add(0, Vec3(0, 0, a), a, m.density, 0);
  const double mass = sim.particles.mass[0];
  sim.particles.x[0].z() = a - mass * g / m.kn;  // at rest on the floor: no bounce to damp
  sim.particles.v[0] = Vec3(v0, 0, 0);
  sim.dt = 2e-6;  // 1/40 of the contact's period 2π sqrt(m/kn)
  sim.ledger.on = true;
  const double t_roll = 2 * v0 / (7 * mu * g);
  while (sim.time < 2 * t_roll) sim.advance();
  const EnergyLedger& l = sim.ledger;
  const double closed = mass * v0 * v0 / 7;
  // The ledger starts after the first step (its friction, μ m g v0 Δt, is not counted: 1e-4 of
  // the closed form here), and the spring's stick-slip at the change to rolling costs a few steps'
  // slip: 0.5 % covers both.
  EXPECT_NEAR(l.friction(), closed, 5e-3 * closed);
  EXPECT_NEAR(sim.particles.v[0].x(), 5.0 / 7.0 * v0, 5e-3 * v0);  // it does roll
  EXPECT_LT(std::abs(l.error()), 1e-3 * closed);
}

// --- A bonded pair pulled apart until the bond breaks: it releases ½ kn s*², s* = F/kn. ---------
TEST(Energy, ABrokenBondReleasesTheEnergyItHeldWhenItBroke) {
  constexpr double kKn = 1e5, kStrength = 2.0, kRadius = 1e-3, kRate = 0.02;
  Simulation sim;
  Material m;
  m.name = "cement";
  m.law = NormalLaw::Liu;
  m.density = 2500;
  m.kn = m.kt = kKn;
  m.tensile_strength = kStrength;
  m.restitution = m.restitution_t = 1;  // no dashpot: what the pull puts in is held until the break
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3::Zero();
  const double u0 = 1e-7;
  sim.particles.add(0, Vec3(-kRadius + u0 / 2, 0, 0), kRadius, m.density, 0);
  sim.particles.add(1, Vec3(kRadius - u0 / 2, 0, 0), kRadius, m.density, 0);
  ASSERT_EQ(sim.bond_present_contacts(false), 1u);
  // Both prescribed, moving apart at kRate: whatever holds them does the bond's work.
  sim.particles.fixed.assign(2, kPrescribed);
  sim.particles.v[0] = Vec3(-kRate / 2, 0, 0);
  sim.particles.v[1] = Vec3(kRate / 2, 0, 0);
  const double s_break = kStrength / kKn;  // eq. 2.21: the tension kn s reaches F
  sim.dt = s_break / kRate / 1000;         // 1,000 steps to the break
  sim.ledger.on = true;
  while (sim.has_bonds() && sim.step < 5000) sim.advance();
  ASSERT_FALSE(sim.has_bonds());
  const double closed = 0.5 * kKn * s_break * s_break;
  // The bond breaks in the first step whose separation s exceeds s*, and the ledger takes its
  // energy at the half step before: within one step's stretch of s*, kRate Δt = s*/1000, so
  // within 2/1000 of ½ kn s*².
  EXPECT_NEAR(sim.ledger.totals.released, closed, 2e-3 * closed);
  // The prescribed motion put that energy in (from the first step on: the compression u0 it
  // started with held ½ kn u0², 1e-6 of it).
  EXPECT_NEAR(sim.ledger.totals.work_prescribed, closed, 2e-3 * closed);
  EXPECT_LT(std::abs(sim.ledger.error()), 2e-3 * closed);
}

// --- Bonded blocks colliding: the balance closes at every step. -------------------------------
// Two cubes of 5 x 5 x 5 bonded spheres (liu law, friction, dashpot) meet head on at 1 m/s; with
// a bond strength that lets the impact break bonds, and with unbreakable bonds. `reversed`: the
// spheres stored in the opposite order.
Simulation bonded_blocks(double strength, bool reversed = false) {
  Simulation sim;
  Material m;
  m.name = "rock";
  m.law = NormalLaw::Liu;
  m.density = 2600;
  m.kn = m.kt = 2e5;
  m.friction_angle = 30;
  m.cohesion = strength;
  m.tensile_strength = strength;
  m.restitution = 0.5;
  m.restitution_t = 0.5;
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3(0, 0, -9.81);
  const double a = 1e-3, pitch = 2 * a;  // touching: the bonds hold no energy at the start
  int id = 0;
  for (int block = 0; block < 2; ++block)
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
          const double x0 = block == 0 ? -5 * pitch - 0.5 * a : 0.5 * a;
          sim.particles.add(id++, Vec3(x0 + i * pitch + (block ? 0.3 * a : 0.0), j * pitch + (block ? 0.4 * a : 0.0), k * pitch), a,
                            m.density, 0);
          sim.particles.v.back() = Vec3(block == 0 ? 0.5 : -0.5, 0, 0);
        }
  if (reversed) {
    std::vector<std::size_t> order(sim.particles.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = order.size() - 1 - k;
    sim.particles.reorder(order);
  }
  sim.bond_present_contacts(false, 1e-6);  // gaps of round-off count as touching
  sim.dt = 0.2 * sim.critical_time_step();
  return sim;
}

// Runs `steps` steps with the ledger and checks |error| <= 1 % of its scale after each (the
// issue's bound; the scheme's own error is O((ω Δt)²) per touch and per break).
void run_checking_balance(Simulation& sim, int steps, double& worst) {
  sim.ledger.on = true;
  worst = 0;
  for (int n = 0; n < steps; ++n) {
    sim.advance();
    if (!sim.ledger.have_reference) continue;
    worst = std::max(worst, std::abs(sim.ledger.error()) / sim.ledger.scale());
  }
}

TEST(Energy, BalanceOfBondedBlocksCollidingClosesWithinOnePercentAtEveryStep) {
  for (double strength : {0.05, 1e9}) {
    Simulation sim = bonded_blocks(strength);
    const std::size_t bonds0 = intact_bonds(sim);
    double worst = 0;
    run_checking_balance(sim, 1500, worst);  // the impact is over by step 1,000
    EXPECT_LT(worst, 0.01) << "strength " << strength;
    const EnergyLedger& l = sim.ledger;
    EXPECT_GT(l.totals.damping_normal, 0.0);
    EXPECT_GT(l.dissipated(), 0.05 * l.scale()) << "the impact dissipates";  // not a balance of nothing
    if (strength < 1) {
      EXPECT_LT(intact_bonds(sim), bonds0) << "the weak bonds break";
      EXPECT_GT(l.totals.released, 0.0);
    } else {
      EXPECT_EQ(intact_bonds(sim), bonds0);
      EXPECT_EQ(l.totals.released, 0.0);
    }
    std::printf("energy balance, bonded blocks (strength %g N): worst |error|/scale %.3g, dissipated %.3g J of %.3g J, released %.3g J\n",
                strength, worst, l.dissipated(), l.scale(), l.totals.released);
  }
}

// A floor under the blocks' lowest row turning about y at 2 rad/s: its contacts take the wall loop
// and put in work.
void add_turning_floor(Simulation& sim) {
  const double a = 1e-3;  // the blocks' radius
  sim.walls.push_back(Wall{"floor", 0, {Vec3(-0.1, -0.1, -a), Vec3(0.1, -0.1, -a), Vec3(0.1, 0.1, -a), Vec3(-0.1, 0.1, -a)}, {}});
  WallMotion turn;
  turn.axis = Vec3::UnitY();
  turn.angular_speed = 2;
  sim.walls[0].start_motion(turn, 0);
}

// The ledger's pass is split over the threads (fixed ranges of particles, pairs and wall contacts,
// each thread its own sums): the bonded blocks, bonds breaking, collide on a floor turning about y,
// whose contacts take the wall loop and put in work. Exact equality: the sums are integers.
TEST(Energy, LedgerHasTheSameBitsOnOneAndTwoThreads) {
  std::vector<double> values[2];
  for (int t : {1, 2}) {
    omp_set_num_threads(t);
    Simulation sim = bonded_blocks(0.05);
    const std::size_t bonds0 = intact_bonds(sim);
    add_turning_floor(sim);
    double worst = 0;
    run_checking_balance(sim, 1000, worst);  // the blocks meet and break bonds by then
    EXPECT_LT(intact_bonds(sim), bonds0) << "bonds break";
    EXPECT_NE(sim.ledger.totals.work_walls, 0.0) << "the floor's contacts count";
    values[t - 1] = sim.ledger.values();
  }
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_EQ(values[0], values[1]);
}

// The pair contacts' forces for the ledger come from the force loop (forces/force_loop.hpp,
// ContactWork), each thread its own blocks: the same bits whatever the storage order. The bonded
// blocks on the turning floor, stored as built on one thread, and stored in the opposite order,
// re-sorted every 7 steps, in blocks of 16 slots on two threads.
TEST(Energy, LedgerHasTheSameBitsForAnyStorageOrder) {
  const int threads_before = omp_get_max_threads();
  std::vector<double> values[2];
  for (const bool reordered : {false, true}) {
    omp_set_num_threads(reordered ? 2 : 1);
    Simulation sim = bonded_blocks(0.05, reordered);
    if (reordered) sim.params.sort_every = 7, sim.params.sort_min_particles = 0, sim.params.load_block = 16;
    add_turning_floor(sim);
    sim.ledger.on = true;
    for (int n = 0; n < 1000; ++n) sim.advance();
    EXPECT_GT(sim.ledger.totals.released, 0.0) << "bonds break";
    values[reordered] = sim.ledger.values();
  }
  omp_set_num_threads(threads_before);
  EXPECT_EQ(values[0], values[1]);
}

// The ledger adds the step's work every step but measures what is held (EnergyLedger::now) only
// where asked (run-stage: the energy log's rows): the figures at a row must be those of measuring
// every step, to the bit (the sums are integers, and what is held depends only on the step). The
// colliding blocks, bonds breaking, on the turning floor, with and without global damping (the
// particles' own work, which a step that does not measure still visits).
TEST(Energy, MeasuringOnlyAtTheRowsGivesTheFiguresOfMeasuringEveryStep) {
  for (double alpha : {0.0, 0.05}) {
    std::vector<std::vector<double>> rows[2];
    for (int every : {1, 50}) {
      Simulation sim = bonded_blocks(0.05);
      sim.params.alpha_r = sim.params.alpha_theta = alpha;
      add_turning_floor(sim);
      sim.ledger.on = true;
      for (int n = 1; n <= 1000; ++n) {
        sim.ledger.measure_now = n % every == 0;
        sim.advance();
        if (n % 50 == 0) rows[every != 1].push_back(sim.ledger.values());
      }
      EXPECT_GT(sim.ledger.totals.released, 0.0) << "bonds break";
    }
    ASSERT_EQ(rows[0].size(), 20u);
    for (std::size_t r = 0; r < rows[0].size(); ++r) EXPECT_EQ(rows[0][r], rows[1][r]) << "row " << r << ", alpha " << alpha;
  }
}

// --- Each step's contact work is its forces times the mean velocities (eq. P32-P34). ------------
// 60 spheres dropped into a box (linear law, dashpot, friction), the list rebuilt often (a small
// skin), re-sorted every 13 steps, two threads in blocks of 16 slots, measuring every 97th step:
// the ledger's dashpot and tangential work must equal each step's contact forces times the mean of
// the velocities before and after it, summed here from the contacts the step reports
// (docs/physics.md eq. P33-P34: f_d n · (v̄_i - v̄_j) Δt and f_t · (v̄_i - v̄_j) Δt + (n x f_t) ·
// (a_i w̄_i + a_j w̄_j) Δt; a wall contact's with v̄_j = 0, the walls standing still), from the
// first step after the ledger's reference on. Tolerance 1e-9 of the sum of the terms' sizes: the
// forces are taken apart here from the step's (f_el = k_n u at x^n), which differ from the law's in
// the last bits; one contact-step's work missed or taken twice is on average 1e-6 of it.
TEST(Energy, ContactWorkIsEachStepsForcesTimesTheMeanVelocities) {
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(2);
  Simulation sim;
  const Material m = linear_material("glass", 2500, 5e4, 25, 0.3);
  sim.materials = MaterialTable({m}, {});
  sim.params.gravity = Vec3(0, 0, -9.81);
  sim.params.sort_every = 13, sim.params.sort_min_particles = 0, sim.params.load_block = 16;
  sim.params.keep_pair_results = true;
  sim.params.skin = 1e-5;  // about the distance a falling sphere covers in 10 steps
  const double side = 0.02;
  const Vec3 c[8] = {{0, 0, 0}, {side, 0, 0}, {side, side, 0}, {0, side, 0}, {0, 0, 0.1}, {side, 0, 0.1}, {side, side, 0.1}, {0, side, 0.1}};
  for (const auto& f : std::vector<std::array<int, 4>>{{0, 1, 2, 3}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}})
    sim.walls.push_back(Wall{"box", 0, {c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, {}});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int k = 0; k < 60; ++k) {  // four by four in a layer, 5 mm apart, each moved up to 0.4 mm
    const double a = 1.5e-3 + 0.5e-3 * u01(rng);
    const Vec3 jitter(0.8e-3 * u01(rng) - 0.4e-3, 0.8e-3 * u01(rng) - 0.4e-3, 0.8e-3 * u01(rng));
    sim.particles.add(k, Vec3(2.5e-3 + 5e-3 * (k % 4), 2.5e-3 + 5e-3 * (k / 4 % 4), 2.5e-3 + 5e-3 * (k / 16)) + jitter, a, m.density, 0);
    sim.particles.w.back() = Vec3(200 * u01(rng) - 100, 200 * u01(rng) - 100, 0);
  }
  sim.dt = 0.2 * sim.critical_time_step();
  const double kn = sim.materials.pair(0, 0).kn;  // the spheres' and the walls' (one material)
  sim.ledger.on = true;
  struct State {
    Vec3 x, v, w;
    double a;
  };
  FixedSum damping, tangential;
  double size = 0;  // the sum of the terms' sizes
  long contact_steps = 0;
  for (int n = 1; n <= 20000; ++n) {
    std::vector<State> before(sim.particles.size());  // by id
    for (std::size_t s = 0; s < sim.particles.size(); ++s)
      before[sim.particles.id[s]] = {sim.particles.x[s], sim.particles.v[s], sim.particles.w[s], sim.particles.radius[s]};
    const bool counted = sim.ledger.have_reference;  // the reference step's work is not
    sim.ledger.measure_now = n % 97 == 0;
    sim.advance();
    if (!counted) continue;
    std::vector<std::size_t> slot(sim.particles.size());
    for (std::size_t s = 0; s < sim.particles.size(); ++s) slot[sim.particles.id[s]] = s;
    const auto mean_v = [&](Index id) { return Vec3(0.5 * (before[id].v + sim.particles.v[slot[id]])); };
    const auto mean_w = [&](Index id) { return Vec3(0.5 * (before[id].w + sim.particles.w[slot[id]])); };
    const auto take = [&](const ContactList& list, std::size_t k, double overlap, const Vec3& dv, const Vec3& arm_w) {
      const Vec3 nk = list.normal[k], force = list.sum[k].force;
      const double f_n = -force.dot(nk);
      const Vec3 f_d = (f_n - kn * overlap) * nk, f_t = force + f_n * nk;
      const double d = f_d.dot(dv) * sim.dt, t = (f_t.dot(dv) + list.sum[k].torque_per_radius.dot(arm_w)) * sim.dt;
      damping.add(d), tangential.add(t);
      size += std::abs(d) + std::abs(t);
      ++contact_steps;
    };
    const ContactList& pairs = sim.pair_contacts();
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const State &i = before[pairs.key_i[k]], &j = before[pairs.key_j[k]];
      take(pairs, k, i.a + j.a - (j.x - i.x).norm(), mean_v(pairs.key_i[k]) - mean_v(pairs.key_j[k]),
           Vec3(i.a * mean_w(pairs.key_i[k]) + j.a * mean_w(pairs.key_j[k])));
    }
    const ContactList& walls = sim.wall_contacts();
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const State& i = before[walls.key_i[k]];
      const double dist = (closest_point(sim.wall_geometry()[walls.key_j[k]], i.x) - i.x).norm();
      take(walls, k, i.a - dist, mean_v(walls.key_i[k]), Vec3(i.a * mean_w(walls.key_i[k])));
    }
  }
  omp_set_num_threads(threads_before);
  EXPECT_EQ(sim.step_threads(), 2);
  EXPECT_GT(contact_steps, 20000) << "contacts begin, hold and end many times";
  EXPECT_GT(sim.neighbour_builds(), 100) << "the list is rebuilt often";
  EXPECT_NEAR(sim.ledger.totals.damping_normal, damping.value(), 1e-9 * size);
  EXPECT_NEAR(sim.ledger.totals.tangential_work, tangential.value(), 1e-9 * size);
  EXPECT_GT(damping.value(), 1e-3 * size) << "the dashpots work";
  EXPECT_GT(std::abs(tangential.value()), 1e-3 * size) << "friction works";
  std::printf("contact work: %ld contact-steps, %ld list builds; dashpot %.9g J (definition %.9g J), tangential %.9g J (%.9g J)\n",
              contact_steps, sim.neighbour_builds(), sim.ledger.totals.damping_normal, damping.value(), sim.ledger.totals.tangential_work,
              tangential.value());
}

// --- A sphere lifted by a tilting wall: the wall's work goes into height, friction, damping. ----
// A floor rotating about the y axis at 2 rad/s carries a sphere resting on it 3 cm from the axis:
// the wall does work on it, and the balance closes.
TEST(Energy, BalanceClosesWhileARotatingWallLiftsASphere) {
  Simulation sim;
  Material m;
  m.name = "glass";
  m.density = 2500;
  m.kn = m.kt = 1e5;
  m.friction_angle = 30;
  m.restitution = 0.3;
  m.restitution_t = 0.5;
  sim.materials = MaterialTable({m}, {});
  const double a = 2e-3;
  sim.walls.push_back(Wall{"paddle", 0, {Vec3(-0.1, -0.1, 0), Vec3(0.1, -0.1, 0), Vec3(0.1, 0.1, 0), Vec3(-0.1, 0.1, 0)}, {}});
  WallMotion turn;
  turn.axis = -Vec3::UnitY();  // x towards z: the side x > 0 rises
  turn.angular_speed = 2;
  sim.walls[0].start_motion(turn, 0);
  sim.particles.add(0, Vec3(0.03, 0, a - 2e-6), a, m.density, 0);
  sim.dt = 0.1 * sim.critical_time_step();
  double worst = 0;
  run_checking_balance(sim, static_cast<int>(0.15 / sim.dt), worst);
  EXPECT_LT(worst, 0.01);
  // The wall works on the sphere (it lifts it, then the sphere rolls down the slope it makes).
  EXPECT_GT(sim.ledger.totals.work_abs, 1e-3 * sim.ledger.scale());
}

TEST(Energy, IntervalTakesTheCommandLineThenTheSceneElseNone) {
  EXPECT_EQ(energy_interval(steps(7), seconds(0.5), 1e-3), 7);
  EXPECT_EQ(energy_interval({}, steps(30), 1e-3), 30);  // the scene's "30 steps"
  EXPECT_EQ(energy_interval({}, seconds(0.5), 1e-3), 500);
  EXPECT_EQ(energy_interval({}, seconds(1e-9), 1e-3), 1);  // at least every step
  EXPECT_EQ(energy_interval({}, {}, 1e-3), 0);     // not asked: no log
}

TEST(Energy, LedgerValuesRoundTripAndAWrongCountIsRefused) {
  EnergyLedger l;
  l.have_reference = true;
  l.reference.potential = 1.5;
  l.now.kinetic_rotation = 0.25;
  l.totals.released = 3;
  l.totals.work_abs = 4;
  EnergyLedger back;
  back.from_values(l.values());
  EXPECT_EQ(back.values(), l.values());
  EXPECT_THROW(back.from_values({1, 2}), std::invalid_argument);
}

TEST(Energy, FixedSumIsTheSameInAnyOrder) {
  const double x[] = {1e-12, 3.7, -2.2e3, 5e-20, 1.0 / 3, -7e-9};
  FixedSum forward, backward;
  for (double v : x) forward.add(v);
  for (int k = 5; k >= 0; --k) backward.add(x[k]);
  EXPECT_EQ(forward.value(), backward.value());
  EXPECT_NEAR(forward.value(), 1e-12 + 3.7 - 2.2e3 + 5e-20 + 1.0 / 3 - 7e-9, 1e-12);
  // A term out of range is kept, not thrown (add() may run in a parallel region), and reported by
  // value(); it reaches a sum it is added into.
  FixedSum big, total;
  big.add(1e12);
  EXPECT_THROW(big.value(), PhysicsError);
  total.add(big);
  EXPECT_THROW(total.value(), PhysicsError);
  FixedSum nan;
  nan.add(std::nan(""));
  EXPECT_THROW(nan.value(), PhysicsError);
}

// Each term is truncated towards zero at 2^-90 J (not rounded, not floored), exactly at any scale
// (exact comparisons: every figure here is a multiple of 2^-90).
TEST(Energy, FixedSumTruncatesEachTermTowardsZeroAt2ToTheMinus90) {
  FixedSum s;
  s.add(0x1.8p-91);  // 0.75 units: truncated to 0
  s.add(-0x1.8p-91);
  EXPECT_EQ(s.value(), 0.0);
  s.add(0x1.8p-90);   // 1.5 units: 1
  EXPECT_EQ(s.value(), 0x1p-90);
  s.add(-0x1.cp-89);  // -3.5 units: -3
  EXPECT_EQ(s.value(), -0x1p-89);
  // Large terms: the lowest bit (2^-17 J at 2^35 J) survives, high and low words both counting.
  FixedSum wide;
  wide.add(0x1.fffffffffffffp35);  // just under 2^36 J: 126 bits in fixed point
  wide.add(-0x1.ffffffffffffep35);
  EXPECT_EQ(wide.value(), 0x1p-17);
}

// add_all (the four-wide pass where the loops run so) against adding the terms one by one, to
// the last unit (FixedSum's ==): terms of every scale from below 2^-90 J to 2^30 J (their sums
// within the range of 2^37 J), a few just under the range of a term (2^36 J), of both signs,
// zeros; counts on both sides of the pass's 4 x 2,048 terms a round and not multiples of 4; a
// term out of range or NaN amid them.
TEST(Energy, AddAllGivesTheBitsOfAddingOneByOne) {
  std::mt19937_64 random(90);
  std::uniform_real_distribution<double> exponent(-100.0, 30.0), unit(-1.0, 1.0);
  std::vector<double> x(20003);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = k % 97 == 0 ? 0.0 : unit(random) * std::exp2(exponent(random));
  x[5] = -0.0, x[6] = 0x1.fffffffffffffp35, x[7] = -0x1.fffffffffffffp35, x[8] = 0x1p-91, x[9] = -0x1.8p-90;
  // Each lane's terms of one sign near the top of the range, their high parts (2^84 units) all
  // different, and different between lanes: a lane's sum of 2,048 of them comes within 2^42 of
  // 2^53 units; one of more would lose odd units (the lanes' losses unlike, so not cancelling).
  // The negative ones a little larger, so that adding them one by one stays within the range.
  std::vector<double> edge(16384);
  for (std::size_t k = 0; k < edge.size(); ++k) {
    const std::size_t lane = k % 4, step = lane < 2 ? lane + 3 : lane - 1;  // 3, 4 (+); 1, 2 (-)
    edge[k] = (lane < 2 ? 1.0 : -1.0) * (0x1.fffffffffffffp35 - static_cast<double>(k / 4 * step) * 0x1p-6);
  }
  const bool simd_was = simd_loops_on();
  for (const bool simd : {false, true}) {
    if (simd && !simd_loops_available()) continue;
    set_simd_loops(simd);
    for (const std::vector<double>* terms : {&x, &edge})
      for (const long n : {0L, 3L, 4L, 1023L, 8192L, 8195L, 16388L, static_cast<long>(terms->size())}) {
        if (n > static_cast<long>(terms->size())) continue;
        FixedSum one_by_one, all;
        for (long k = 0; k < n; ++k) one_by_one.add((*terms)[k]);
        add_all(all, terms->data(), n);
        EXPECT_TRUE(all == one_by_one) << "simd " << simd << ", " << n << " terms";
        if (terms == &x && n > 0) EXPECT_NE(all.value(), 0.0);
      }
    for (const double bad : {1e12, -0x1p36, std::nan("")}) {
      std::vector<double> with_bad(x.begin(), x.begin() + 9000);
      with_bad[8500] = bad;  // in the second round of 8,192
      FixedSum one_by_one, all;
      for (double v : with_bad) one_by_one.add(v);
      add_all(all, with_bad.data(), static_cast<long>(with_bad.size()));
      EXPECT_TRUE(all == one_by_one) << "simd " << simd << ", " << bad;
      EXPECT_THROW(all.value(), PhysicsError);
    }
  }
  set_simd_loops(simd_was);
}

}  // namespace
}  // namespace dem
