// The force loop's four-wide versions (simd/simd.hpp) are speed only. Pass 1 (forces/find_contacts.hpp,
// which candidates are contacts) must decide exactly as the plain loop and as the definition
// (|x_j - x_i| < a_i + a_j through the nearest image, or bonded; the neighbour list never pairs
// two fixed particles), with the same separations to the bit; pass 2 (forces/pair_law_four_wide.hpp,
// every normal law) must end a run with the plain loops' bits, with everything the law has: two
// materials, fixed particles, periodic boundaries, sticking and sliding springs, bonds with
// cohesion, clipped viscous attraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "core/error.hpp"
#include "generation/fill.hpp"
#include "forces/find_contacts.hpp"
#include "simd/simd.hpp"
#include "sim/simulation.hpp"

#include "draw_vec.hpp"
#include "same_bits.hpp"

namespace dem {
namespace {

struct Pass1Result {
  int m = 0;
  std::vector<int> contact;
  std::vector<double> dx, dy, dz;
  std::vector<std::uint8_t> active, bonded;
  std::vector<Vec3> spring;
};

// Random polydisperse particles in a box periodic along x and y, a third of them fixed; candidates
// are random pairs (never two fixed particles: the neighbour list leaves those out), a third of
// them moved to touch within a few ulps of a_i + a_j (either side), some across the periodic
// boundaries; random bonds and random contacts of the last step.
struct Pass1Case {
  Particles p;
  ContactList pc;
  PeriodicBox box;

  explicit Pass1Case(int candidates) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    box.axis = {true, true, false};
    box.lo = Vec3(-1, 0, 0), box.hi = Vec3(2, 4, 5);
    for (int n = 0; n < 400; ++n) {
      p.add(n, Vec3(-1 + 3 * u(rng), 4 * u(rng), 5 * u(rng)), 0.05 + 0.45 * u(rng), 1000, 0);
      p.fixed[n] = u(rng) < 0.3;
    }
    std::uniform_int_distribution<int> slot(0, 399);
    pc.resize(candidates);
    for (int k = 0; k < candidates; ++k) {
      int i = slot(rng), j = slot(rng);
      while (j == i || (p.fixed[i] && p.fixed[j])) j = slot(rng);
      if (u(rng) < 0.35) {  // j placed at a_i + a_j from i, give or take a few ulps, maybe across a boundary
        const Vec3 dir = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        const double r = p.radius[i] + p.radius[j];
        double dist = r;
        for (int ulps = static_cast<int>(u(rng) * 7) - 3; ulps != 0; ulps += ulps > 0 ? -1 : 1)
          dist = std::nextafter(dist, ulps > 0 ? 10.0 : 0.0);
        Vec3 xj = p.x[i] + dist * dir;
        Vec3i image = Vec3i::Zero();
        box.wrap_far(xj, image);
        if (xj.z() > 0 && xj.z() < 5) p.x[j] = xj;
      }
      pc.slot_i[k] = i, pc.slot_j[k] = j;
      pc.bonded[k] = u(rng) < 0.1;
      pc.active[k] = u(rng) < 0.5;
      pc.spring[k] = pc.active[k] ? Vec3(1, 2, 3) : Vec3::Zero();
      pc.sum[k] = pc.active[k] ? ContactSum{Vec3(4, 5, 6), Vec3(7, 8, 9)} : ContactSum();
    }
  }

  // Pass 1 over [first, last) of a copy of the candidates.
  Pass1Result run(long first, long last) const {
    ContactList c = pc;
    Pass1Result r;
    const std::size_t room = last - first + kFoundPadding;
    r.contact.resize(room), r.dx.resize(room), r.dy.resize(room), r.dz.resize(room);
    r.m = find_contacts<true>(CandidateArrays(p, c, nullptr, false), box, first, last, {r.contact.data(), r.dx.data(), r.dy.data(), r.dz.data()},
                                  simd_loops_on());
    r.contact.resize(r.m), r.dx.resize(r.m), r.dy.resize(r.m), r.dz.resize(r.m);
    r.active = c.active, r.bonded = c.bonded, r.spring = c.spring;
    return r;
  }
};

// Chunks of 1 to 9 candidates and a long one, at odd offsets: the four-wide loop and the plain
// loop that finishes a chunk's last one to three candidates both run. (Without AVX2 both runs
// take the plain loop, which is then still checked against the definition.)
TEST(SimdLoops, PassOneDecidesAsTheDefinitionWithThePlainLoopsBits) {
  const Pass1Case c(2000);
  struct Range {
    long first, last;
  };
  std::vector<Range> ranges = {{3, 1700}};
  for (long n = 1; n <= 9; ++n) ranges.push_back({1700 + 10 * n + n % 3, 1700 + 10 * n + n % 3 + n});
  int near_threshold = 0, across_boundary = 0;
  for (const Range& range : ranges) {
    set_simd_loops(false);
    const Pass1Result plain = c.run(range.first, range.last);
    set_simd_loops(true);
    const Pass1Result wide = c.run(range.first, range.last);
    const std::string what = "candidates " + std::to_string(range.first) + " to " + std::to_string(range.last);
    ASSERT_EQ(plain.m, wide.m) << what;
    EXPECT_EQ(plain.contact, wide.contact) << what;
    EXPECT_TRUE(same_bits(plain.dx, wide.dx) && same_bits(plain.dy, wide.dy) && same_bits(plain.dz, wide.dz)) << what;
    EXPECT_EQ(plain.active, wide.active) << what;
    EXPECT_EQ(plain.bonded, wide.bonded) << what;
    EXPECT_TRUE(same_bits(plain.spring, wide.spring)) << what;
    // The definition, candidate by candidate.
    int e = 0;
    for (long k = range.first; k < range.last; ++k) {
      const int i = c.pc.slot_i[k], j = c.pc.slot_j[k];
      const Vec3 d = c.box.nearest(c.p.x[j] - c.p.x[i]);
      const double r = c.p.radius[i] + c.p.radius[j];
      const bool contact = d.squaredNorm() < r * r || c.pc.bonded[k];
      near_threshold += std::abs(d.norm() - r) < 1e-12 * r;
      across_boundary += contact && d != c.p.x[j] - c.p.x[i];
      ASSERT_EQ(wide.active[k], contact) << what << ", candidate " << k;
      EXPECT_EQ(wide.bonded[k], c.pc.bonded[k]) << what << ", candidate " << k;
      const bool lost = c.pc.active[k] && !contact;
      EXPECT_EQ(wide.spring[k], lost ? Vec3::Zero() : c.pc.spring[k]) << what << ", candidate " << k;
      if (contact) {
        ASSERT_LT(e, wide.m);
        EXPECT_EQ(wide.contact[e], k);
        EXPECT_EQ(Vec3(wide.dx[e], wide.dy[e], wide.dz[e]), d);
        ++e;
      }
    }
    EXPECT_EQ(e, wide.m) << what;
  }
  // (Later placements move some particles of earlier ones: about 120 pairs stay within ulps.)
  EXPECT_GT(near_threshold, 80) << "the case must test pairs within ulps of touching";
  EXPECT_GT(across_boundary, 20) << "the case must test contacts across the periodic boundaries";
}

// Spheres of two materials (one clips viscous attraction) with random speeds, grown by 15 % (or
// `growth`) where they were placed apart, so that they press on each other (a dense, jammed packing: 65 % of the
// volume), in a box periodic along x and y, a floor of them fixed; after 400 steps every contact present is
// bonded (cohesion: the Cundall law's bonded failure surface), then 1000 steps more, in which the
// bonds break as their particles separate (SPEC §6 Decision (separation): most within 50 steps) and
// the contacts present are bonded again every 40 steps.
Simulation law_scene(double growth = 1.15) {
  Simulation sim;
  Material a, b;
  a.name = "a", b.name = "b";
  a.density = b.density = 2500;
  a.kn = a.kt = 5e4, b.kn = 8e4, b.kt = 6e4;
  a.friction_angle = 20, b.friction_angle = 35;
  a.restitution = 0.3, b.restitution = 0.7;
  a.cohesion = b.cohesion = 0.02;
  a.no_viscous_attraction = true;
  sim.materials = MaterialTable({a, b}, {});
  const double L = 0.02;
  const Vec3 lo(0, 0, 0), hi(L, L, L);
  for (bool side : {false, true}) sim.walls.push_back(Wall{"w", 0, box_face(lo, hi, 2, side), {}});
  PeriodicBox box;
  box.axis = {true, true, false};
  box.lo = lo, box.hi = hi;
  GenerationSpec g;
  g.box_min = lo;
  g.box_max = hi;
  g.count = 300;
  g.radius_min = 0.0010;
  g.radius_max = 0.0018;
  g.material_fractions = {{0, 0.5}, {1, 0.5}};
  std::mt19937_64 rng(5);
  fill_random(sim, g, rng);
  sim.set_periodic(box);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (std::size_t k = 0; k < sim.particles.size(); ++k) {
    sim.particles.radius[k] *= growth;
    sim.particles.mass[k] *= growth * growth * growth;
    sim.particles.v[k] = draw_vec(u, rng);
    sim.particles.fixed[k] = sim.particles.x[k].z() < 0.25 * L;
    if (sim.particles.fixed[k]) sim.particles.v[k] = Vec3::Zero();
  }
  sim.dt = 0.1 * sim.critical_time_step();
  return sim;
}

// The four-wide law ends with the plain loops' bits: runs keeping every pair contact's normal and
// keeping none (SimParams::keep_pair_results false), with blocks of 256 slots and of 8.
TEST(SimdLoops, LawEndsARunWithThePlainLoopsBits) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2 on this processor: only the plain loops run";
  for (const long block : {256L, 8L}) {
    Simulation plain = law_scene(), kept = law_scene(), lean = law_scene();
    ASSERT_GT(std::count(plain.particles.fixed.begin(), plain.particles.fixed.end(), 1), 20);
    long broken = 0;  // in the plain run
    const auto bonds = [](const Simulation& sim) {
      return static_cast<long>(std::count(sim.pair_contacts().bonded.begin(), sim.pair_contacts().bonded.end(), 1));
    };
    lean.params.keep_pair_results = false;
    for (Simulation* sim : {&plain, &kept, &lean}) {
      sim->params.load_block = block;
      set_simd_loops(sim != &plain);
      for (int s = 0; s < 400; ++s) sim->advance();
      EXPECT_GT(sim->bond_present_contacts(false), 50u);
      for (int s = 1; s <= 1000; ++s) {
        const long before = bonds(*sim);
        sim->advance();
        if (sim == &plain) broken += before - bonds(*sim);
        if (s % 40 == 0 && s < 1000) sim->bond_present_contacts(false);
      }
    }
    set_simd_loops(true);
    ASSERT_GT(bonds(plain), 5) << "bonded lanes to the end";
    std::printf("  bonds at the end %ld, broken %ld\n", bonds(plain), broken);
    EXPECT_GT(broken, 200) << "the run must break bonds (on both paths, compared below)";
    for (const Simulation* wide : {&kept, &lean}) {
      const std::string what = std::string(wide == &kept ? "normals kept" : "no normals") + ", blocks of " + std::to_string(block);
      EXPECT_TRUE(same_bits(plain.particles.x, wide->particles.x)) << what;
      EXPECT_TRUE(same_bits(plain.particles.v, wide->particles.v)) << what;
      EXPECT_TRUE(same_bits(plain.particles.w, wide->particles.w)) << what;
      EXPECT_TRUE(same_bits(plain.pair_contacts().spring, wide->pair_contacts().spring)) << what;
      EXPECT_TRUE(same_bits(plain.pair_contacts().bonded, wide->pair_contacts().bonded)) << what;
    }
  }
}

// Hertz-Mindlin, and the Cundall law, with each rolling law (ContactModel::four_wide: the same
// templates over four lanes) end a run with the plain loops' bits: law_scene's jammed, periodic
// packing with its fixed floor, grown by 22 % (about 1.4 contacts per sphere, so that the chunks
// hold enough contacts for the four-wide law), its materials made Hertz-Mindlin (two moduli and
// restitutions, one clipping viscous attraction) or kept Cundall, one friction angle of 10 degrees
// (so that many contacts slide), 300 steps, every contact bonded (the four-wide loop's bonded
// variant), 300 more; Hertz-Mindlin also with the explicit dashpot (docs/contact-laws.md eq. D7),
// its own compiled loop (a scene of both forms runs the per-contact loop:
// ForceLoop.PerContactLoopTakesEachPairsDashpot). Positions, velocities, spins, springs, rolling
// histories, dashpot marks and bond flags, of pair and wall contacts, are compared bit for bit: any
// lane that rounds otherwise than the plain loop shows. The runs must exercise sliding contacts (counted in the plain run:
// the spring held on the Coulomb limit |s| = mu f_n, to 1e-12 relative: radial return's rounding).
TEST(SimdLoops, HertzMindlinAndRollingLawsEndARunWithThePlainLoopsBits) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2 on this processor: only the plain loops run";
  static_assert(ContactModel<HertzNormal, MindlinSpring, NoRolling>::four_wide &&
                ContactModel<HertzNormal, MindlinSpring, ConstantTorque>::four_wide &&
                ContactModel<HertzNormal, MindlinSpring, ElasticPlasticRolling>::four_wide);
  constexpr double kFriction = 10;  // degrees
  struct Case {
    bool hertz;
    RollingLaw rolling;
    bool explicit_dashpot;
  };
  std::vector<Case> cases;
  for (const bool hertz : {true, false})
    for (const RollingLaw rolling : {RollingLaw::None, RollingLaw::ConstantTorque, RollingLaw::ElasticPlastic})
      if (hertz || rolling != RollingLaw::None) cases.push_back({hertz, rolling, false});  // cundall alone: LawEndsARunWithThePlainLoopsBits
  cases.push_back({true, RollingLaw::None, true});
  for (const Case& c : cases) {
    const bool hertz = c.hertz;  // plain names, not structured bindings: the scene's lambda captures them
    const RollingLaw rolling = c.rolling;
    const bool explicit_dashpot = c.explicit_dashpot;
    auto scene = [&]() {
      Simulation sim = law_scene(1.22);
      std::vector<Material> m = sim.materials.materials();
      for (Material& x : m) {
        if (hertz) x.law = NormalLaw::Hertz, x.tangential = TangentialLaw::Mindlin;
        x.rolling = rolling;
        x.poisson_ratio = 0.3, x.rolling_friction = 0.1, x.friction_angle = kFriction;
      }
      m[0].young_modulus = 5e7, m[1].young_modulus = 8e7;
      for (Material& x : m) x.explicit_dashpot = explicit_dashpot;
      sim.materials = MaterialTable(m, {});
      sim.dt = 0.1 * sim.critical_time_step();
      return sim;
    };
    Simulation plain = scene(), wide = scene();
    const ForceVariant variant = choose_force_variant(plain.materials, false);
    EXPECT_TRUE(variant && variant->explicit_dashpot == explicit_dashpot) << variant_name(variant);
    for (Simulation* sim : {&plain, &wide}) {
      set_simd_loops(sim == &wide);
      for (int s = 0; s < 300; ++s) sim->advance();
      EXPECT_GT(sim->bond_present_contacts(false), 50u);
      for (int s = 0; s < 300; ++s) sim->advance();
    }
    set_simd_loops(true);
    const ContactList& pc = plain.pair_contacts();
    long contacts = 0, unbonded = 0, sliding = 0;
    const double mu = std::tan(kFriction * std::acos(-1.0) / 180);
    for (std::size_t k = 0; k < pc.size(); ++k) {
      if (!pc.active[k]) continue;
      ++contacts;
      if (pc.bonded[k]) continue;
      ++unbonded;
      const double fn = -pc.sum[k].force.dot(pc.normal[k]);
      sliding += fn > 0 && std::abs(pc.spring[k].norm() - mu * fn) <= 1e-12 * mu * fn;
    }
    const std::string what = std::string(hertz ? "hertz + mindlin + " : "cundall + ") + std::string(rolling_law_name(rolling)) +
                             (explicit_dashpot ? ", explicit dashpot" : "");
    std::printf("  %s: %ld contacts at the end, %ld unbonded, %ld of them sliding\n", what.c_str(), contacts, unbonded, sliding);
    ASSERT_GT(contacts, 80) << what;
    EXPECT_GT(sliding, 10) << what << ": the run must exercise sliding";
    EXPECT_TRUE(same_bits(plain.particles.x, wide.particles.x)) << what;
    EXPECT_TRUE(same_bits(plain.particles.v, wide.particles.v)) << what;
    EXPECT_TRUE(same_bits(plain.particles.w, wide.particles.w)) << what;
    // The wall contacts' law runs eight at a time too (forces/wall_law.hpp): the floor and the lid
    // hold more than eight contacts, so both the eights and the tail of four or fewer run.
    const ContactList& wc = plain.wall_contacts();
    const long on_walls = std::count(wc.active.begin(), wc.active.end(), 1);
    std::printf("  %s: %ld wall contacts at the end\n", what.c_str(), on_walls);
    EXPECT_GT(on_walls, 12) << what;
    for (const bool walls : {false, true}) {
      const ContactList& a = walls ? wc : pc;
      const ContactList& b = walls ? wide.wall_contacts() : wide.pair_contacts();
      const std::string where = what + (walls ? ", wall contacts" : ", pair contacts");
      EXPECT_TRUE(same_bits(a.spring, b.spring)) << where;
      EXPECT_TRUE(same_bits(a.rolling, b.rolling)) << where;
      EXPECT_TRUE(same_bits(a.dashpot, b.dashpot)) << where;
      EXPECT_TRUE(same_bits(a.bonded, b.bonded)) << where;
    }
  }
}

// The bonded laws (liu, mendes with tension: epsilon = 1e-4 < 1/e, mendes without: epsilon = 0.5)
// end a run with the plain loops' bits: law_scene's packing (grown by 22 %: chunks of enough
// contacts for the four-wide law) made of the law, with tensile strength F = cohesion C = 0.2 N, 300
// steps, every contact bonded (the walls' too), then the lid, bonded to the top spheres, pulled up
// and sideways for 700 steps: the block between it and the fixed floor is stretched and sheared
// until its bonds break. Counted in the plain run: bonds held in tension (u < 0), bonds on their
// cohesive failure surface (|s| = C + mu f_n, to 1e-12 relative: radial return's rounding) and
// bonds broken, each of which must occur (else the comparison would not test that branch);
// positions, velocities, spins, springs, dashpot marks and bond flags, pair and wall contacts,
// are compared bit for bit. Each step, the count of bonds the force loop keeps must be the flags'.
TEST(SimdLoops, BondedLiuAndMendesLawsEndARunWithThePlainLoopsBits) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2 on this processor: only the plain loops run";
  static_assert(ContactModel<LiuNormal>::four_wide && ContactModel<MendesNormal>::four_wide);
  struct Case {
    NormalLaw law;
    double epsilon;
    const char* name;
  };
  for (const Case& c : {Case{NormalLaw::Liu, 1e-4, "liu"}, Case{NormalLaw::Mendes, 1e-4, "mendes, epsilon 1e-4"},
                        Case{NormalLaw::Mendes, 0.5, "mendes, epsilon 0.5"}}) {
    auto scene = [&]() {
      Simulation sim = law_scene(1.22);
      std::vector<Material> m = sim.materials.materials();
      for (Material& x : m) x.law = c.law, x.epsilon = c.epsilon, x.tensile_strength = 0.2, x.cohesion = 0.2;
      sim.materials = MaterialTable(m, {});
      sim.dt = 0.1 * sim.critical_time_step();
      return sim;
    };
    Simulation plain = scene(), wide = scene();
    long tension = 0, shear = 0, broken = 0;  // in the plain run
    for (Simulation* sim : {&plain, &wide}) {
      set_simd_loops(sim == &wide);
      for (int s = 0; s < 300; ++s) sim->advance();
      EXPECT_GT(sim->bond_present_contacts(true), 50u);
      WallMotion pull;
      pull.velocity = Vec3(0.1, 0, 0.1);  // m/s
      sim->walls[1].start_motion(pull, sim->time);
      const auto bonds = [&] {
        const ContactList& pc = sim->pair_contacts();  // a view, made when asked
        return static_cast<long>(std::count(pc.bonded.begin(), pc.bonded.end(), 1));
      };
      long held = bonds();
      for (int s = 0; s < 700; ++s) {
        sim->advance();
        // The count the force loop keeps (each bond it breaks) is the flags' count, walls' included.
        const ContactList& wc = sim->wall_contacts();
        ASSERT_EQ(sim->bonds(), bonds() + std::count(wc.bonded.begin(), wc.bonded.end(), 1)) << c.name << ", step " << s;
        if (sim != &plain) continue;
        broken += held - bonds();
        held = bonds();
        const ContactList& pc = sim->pair_contacts();
        const Particles& p = sim->particles;
        for (std::size_t k = 0; k < pc.size(); ++k) {
          if (!pc.active[k] || !pc.bonded[k]) continue;
          const int i = pc.slot_i[k], j = pc.slot_j[k];
          const PairParams& q = sim->materials.pair(p.material[i], p.material[j]);
          tension += p.radius[i] + p.radius[j] < sim->periodic.nearest(p.x[j] - p.x[i]).norm();
          const double tau = q.cohesion + q.mu * -pc.sum[k].force.dot(pc.normal[k]);
          shear += tau > 0 && std::abs(pc.spring[k].norm() - tau) <= 1e-12 * tau;
        }
      }
    }
    set_simd_loops(true);
    const ContactList& pc = plain.pair_contacts();
    std::printf("  %s: %ld bond-steps in tension, %ld on the cohesive surface, %ld bonds broken, %ld left\n", c.name, tension, shear,
                broken, static_cast<long>(std::count(pc.bonded.begin(), pc.bonded.end(), 1)));
    EXPECT_GT(tension, 100) << c.name << ": the run must hold bonds in tension";
    EXPECT_GT(shear, 10) << c.name << ": the run must take bonds onto their cohesive failure surface";
    EXPECT_GT(broken, 50) << c.name << ": the run must break bonds";
    EXPECT_TRUE(same_bits(plain.particles.x, wide.particles.x)) << c.name;
    EXPECT_TRUE(same_bits(plain.particles.v, wide.particles.v)) << c.name;
    EXPECT_TRUE(same_bits(plain.particles.w, wide.particles.w)) << c.name;
    for (const bool walls : {false, true}) {
      const ContactList& a = walls ? plain.wall_contacts() : pc;
      const ContactList& b = walls ? wide.wall_contacts() : wide.pair_contacts();
      const std::string what = std::string(c.name) + (walls ? ", wall contacts" : ", pair contacts");
      EXPECT_TRUE(same_bits(a.spring, b.spring)) << what;
      EXPECT_TRUE(same_bits(a.dashpot, b.dashpot)) << what;
      EXPECT_TRUE(same_bits(a.bonded, b.bonded)) << what;
    }
  }
}

// The law also returns the largest overlap relative to the smaller radius, which stops a run past
// simulation.max_overlap. Its definition, max over touching pairs of (a_i + a_j - |x_j - x_i|) /
// min(a_i, a_j) through the nearest image, here lies in a pair of the jammed law_scene (the walls'
// overlaps are smaller): a limit just under it stops the first step, one just above it does not,
// in both versions. (The margin 1e-9 is far above the rounding of one division, far below the gap
// between the largest overlap and the next.)
TEST(SimdLoops, LawFindsTheLargestOverlapOfTheDefinition) {
  if (!simd_loops_available()) GTEST_SKIP() << "no AVX2 on this processor: only the plain loops run";
  const Simulation scene = law_scene();
  const Particles& p = scene.particles;
  double largest = 0, next = 0, walls = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if (p.fixed[i] && p.fixed[j]) continue;
      const double u = (p.radius[i] + p.radius[j] - scene.periodic.nearest(p.x[j] - p.x[i]).norm()) / std::min(p.radius[i], p.radius[j]);
      if (u > largest) next = largest, largest = u;
      else next = std::max(next, u);
    }
    const double L = 0.02;  // law_scene's floor and lid
    walls = std::max({walls, (p.radius[i] - p.x[i].z()) / p.radius[i], (p.radius[i] - (L - p.x[i].z())) / p.radius[i]});
  }
  ASSERT_GT(largest, 0.05);
  ASSERT_GT(largest, walls * (1 + 1e-6));
  ASSERT_GT(largest, next * (1 + 1e-6));
  for (bool wide : {false, true}) {
    set_simd_loops(wide);
    Simulation below = scene, above = scene;
    below.params.max_overlap = largest * (1 - 1e-9);
    above.params.max_overlap = largest * (1 + 1e-9);
    EXPECT_THROW(below.advance(), PhysicsError) << (wide ? "four-wide" : "plain");
    EXPECT_NO_THROW(above.advance()) << (wide ? "four-wide" : "plain");
  }
  set_simd_loops(true);
}

}  // namespace
}  // namespace dem
