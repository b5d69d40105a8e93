// Strict scene validation: each malformed input is rejected with a message that names the file,
// the line, the key, the value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/scene_parser.hpp"
#include "scene_rejects.hpp"

namespace dem {
namespace {

const std::string kValid = R"([simulation]
gravity = [0.0, 0.0, -9.81]

[[material]]
name = "glass"
density = 2500.0
kn = 5.0e4
friction_angle = 25.0
restitution = 0.3

[[wall]]
name = "box"
material = "glass"
type = "box"
min = [0.0, 0.0, 0.0]
max = [0.02, 0.02, 0.05]

[generation]
box_min = [0.0, 0.0, 0.0]
box_max = [0.02, 0.02, 0.05]
count = 100
radius_min = 0.001
radius_max = 0.002
materials = { glass = 1.0 }

[[stage]]
name = "shake"
duration = 0.1

[[stage.motion]]
wall = "box"
type = "vibrate"
direction = [0.0, 0.0, 1.0]
frequency = 20.0
acceleration = 29.43
)";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  if (pos == std::string::npos) throw std::logic_error("test text not found: " + from);
  return s.replace(pos, from.size(), to);
}

// Restitution 0 (perfectly plastic) is accepted: critical damping, gamma = 1 (docs/contact-laws.md,
// "The dashpot in time"); its tangential restitution follows it unless given.
TEST(SceneParser, RestitutionZeroIsCriticalDamping) {
  const Scene s = parse_scene(replace(kValid, "restitution = 0.3", "restitution = 0.0"), "scene.toml");
  EXPECT_EQ(s.materials[0].restitution, 0.0);
  const MaterialTable t(s.materials, s.mixing, s.pairs);
  EXPECT_EQ(t.pair(0, 0).gamma_n, 1.0);
}

// explicit_dashpot (docs/contact-laws.md eq. D7) is off unless asked; asked by a material it holds
// for that material's pairs, and a [[pair]] may ask it for itself.
TEST(SceneParser, ExplicitDashpotParses) {
  EXPECT_FALSE(parse_scene(kValid, "scene.toml").materials[0].explicit_dashpot);
  const std::string two = replace(kValid, "[[wall]]", "[[material]]\nname = \"steel\"\ndensity = 7800.0\nkn = 1e5\nexplicit_dashpot = true\n\n"
                                                     "[[pair]]\nmaterials = [\"glass\", \"glass\"]\nexplicit_dashpot = true\n\n[[wall]]");
  const Scene s = parse_scene(two, "scene.toml");
  EXPECT_FALSE(s.materials[0].explicit_dashpot);
  EXPECT_TRUE(s.materials[1].explicit_dashpot);
  const MaterialTable t(s.materials, s.mixing, s.pairs);
  EXPECT_TRUE(t.pair(0, 0).explicit_dashpot) << "the pair's own";
  EXPECT_TRUE(t.pair(0, 1).explicit_dashpot) << "either material's";
  const Scene plain = parse_scene(replace(two, "materials = [\"glass\", \"glass\"]\nexplicit_dashpot = true", "materials = [\"glass\", \"glass\"]"), "scene.toml");
  EXPECT_FALSE(MaterialTable(plain.materials, plain.mixing, plain.pairs).pair(0, 0).explicit_dashpot);
}

// A hertz material reads its own keys (young_modulus, poisson_ratio), kt without a default (there
// is no kn to take it from), and its pair constants follow eq. H2 (by hand).
TEST(SceneParser, HertzMaterialParses) {
  const Scene s = parse_scene(replace(replace(kValid, "kn = 5.0e4", "law = \"hertz\"\nyoung_modulus = 2.0e7\npoisson_ratio = 0.25\nkt = 4.0e4"),
                                      "restitution = 0.3", "tangential_restitution = 0.5"),
                              "scene.toml");
  ASSERT_EQ(s.materials[0].law, NormalLaw::Hertz);
  EXPECT_EQ(s.materials[0].young_modulus, 2e7);
  EXPECT_EQ(s.materials[0].kt, 4e4);
  EXPECT_EQ(s.materials[0].restitution, 1.0);
  const MaterialTable t(s.materials, s.mixing, s.pairs);
  EXPECT_NEAR(t.pair(0, 0).hertz_modulus, 4.0 / 3.0 * 2e7 / (2 * (1 - 0.25 * 0.25)), 1e-6);
}

// Hertz-Mindlin, as a LIGGGHTS scene's `model hertz tangential history`; and a [[pair]] that
// joins a mindlin material with a coulomb one by naming the tangential law.
TEST(SceneParser, HertzMindlinMaterialParses) {
  const std::string mindlin = replace(kValid, "kn = 5.0e4", "law = \"hertz\"\ntangential = \"mindlin\"\nyoung_modulus = 2.0e7\npoisson_ratio = 0.25");
  const Scene s = parse_scene(mindlin, "scene.toml");
  ASSERT_EQ(s.materials[0].tangential, TangentialLaw::Mindlin);
  const MaterialTable t(s.materials, s.mixing, s.pairs);
  const double g = 2e7 / (2 * 1.25);
  EXPECT_NEAR(t.pair(0, 0).mindlin_modulus, 8 / (2 * (2 - 0.25) / g), 1e-6);
  const Scene mixed = parse_scene(replace(mindlin, "[[wall]]", "[[material]]\nname = \"steel\"\nlaw = \"hertz\"\ndensity = 7800.0\n"
                                                               "young_modulus = 2e11\npoisson_ratio = 0.3\nkt = 1e6\n\n[[pair]]\n"
                                                               "materials = [\"glass\", \"steel\"]\ntangential = \"mindlin\"\n\n[[wall]]"),
                                  "scene.toml");
  const MaterialTable m(mixed.materials, mixed.mixing, mixed.pairs);
  EXPECT_EQ(m.pair(1, 1).tangential, TangentialLaw::Coulomb);
  EXPECT_EQ(m.pair(0, 1).tangential, TangentialLaw::Mindlin);
  EXPECT_GT(m.pair(0, 1).mindlin_modulus, 0);
}

TEST(SceneParser, ValidSceneParses) {
  const Scene s = parse_scene(kValid, "scene.toml");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].kt, 5e4) << "kt defaults to kn";
  EXPECT_EQ(s.materials[0].restitution_t, 0.3) << "tangential restitution defaults to restitution";
  EXPECT_EQ(s.walls.size(), 6u) << "a box is six quads";
  EXPECT_EQ(s.walls[4].name, "box.zmin");
  ASSERT_TRUE(s.generation);
  EXPECT_EQ(s.generation->count, 100);
  ASSERT_EQ(s.stages.size(), 1u);
  const double w = 2 * M_PI * 20;
  EXPECT_DOUBLE_EQ(s.stages[0].motions[0].motion.amplitude, 29.43 / (w * w)) << "acceleration -> amplitude A = a / (2 pi f)^2";
}

// A stage's own gravity (docs/scene.md, [[stage]]): read where given, absent otherwise; three
// finite numbers, as [simulation] gravity.
TEST(SceneParser, StageGravity) {
  const Scene plain = parse_scene(kValid, "scene.toml");
  EXPECT_FALSE(plain.stages[0].gravity.has_value());
  const Scene heavy = parse_scene(replace(kValid, "duration = 0.1\n", "duration = 0.1\ngravity = [0.0, 0.0, -20.0]\n"), "scene.toml");
  ASSERT_TRUE(heavy.stages[0].gravity.has_value());
  EXPECT_EQ(*heavy.stages[0].gravity, Vec3(0, 0, -20));
  expect_rejected({"stage gravity of two numbers", replace(kValid, "duration = 0.1\n", "duration = 0.1\ngravity = [0.0, -20.0]\n"),
                   {"stage[0].gravity", "expected an array of 3 numbers"}});
}

using BadCase = BadScene;

class SceneRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneRejects, WithAClearMessage) {
  const BadCase& c = GetParam();
  expect_rejected(c);
}

// A stage action removing `region` (an inline table), for the region cases below.
std::string remove_region(const std::string& region) { return "\n[[stage.action]]\ntype = \"remove\"\nregion = " + region + "\n"; }

std::vector<BadCase> bad_cases() {
  return {
      {"syntax error", replace(kValid, "density = 2500.0", "density = = 2500.0"), {"scene.toml:6", "TOML syntax error"}},
      {"unknown top-level key", kValid + "\n[solver]\norder = 2\n", {"solver", "unknown key"}},
      {"unknown material key", replace(kValid, "density = 2500.0", "density = 2500.0\ndensty = 1.0"),
       {"scene.toml:7", "material[0].densty", "unknown key", "allowed here"}},
      {"negative density", replace(kValid, "density = 2500.0", "density = -5.0"),
       {"scene.toml:6", "material[0].density = -5", "out of range", "kg/m^3"}},
      {"density as string", replace(kValid, "density = 2500.0", "density = \"heavy\""),
       {"material[0].density = \"heavy\"", "expected a number", "got a string"}},
      {"zero stiffness", replace(kValid, "kn = 5.0e4", "kn = 0.0"), {"material[0].kn = 0", "(0, inf) N/m"}},
      {"restitution above one", replace(kValid, "restitution = 0.3", "restitution = 1.5"),
       {"material[0].restitution = 1.5", "[0, 1]"}},
      {"friction angle 90", replace(kValid, "friction_angle = 25.0", "friction_angle = 90.0"),
       {"material[0].friction_angle = 90", "[0, 90) degrees"}},
      {"unknown contact law", replace(kValid, "density = 2500.0", "density = 2500.0\nlaw = \"hooke\""),
       {"material[0].law = \"hooke\"", "allowed \"cundall\", \"liu\", \"mendes\", \"hertz\""}},
      {"no material", replace(kValid, "[[material]]\nname = \"glass\"", "[[materia]]\nname = \"glass\""),
       {"no [[material]] defined"}},
      {"duplicate material", replace(kValid, "[[wall]]", "[[material]]\nname = \"glass\"\ndensity = 1.0\nkn = 1.0\n\n[[wall]]"),
       {"material[1].name = \"glass\"", "duplicate"}},
      {"wall with unknown material", replace(kValid, "material = \"glass\"\ntype", "material = \"rubber\"\ntype"),
       {"wall[0].material = \"rubber\"", "no material of that name", "\"glass\""}},
      {"unknown wall type", replace(kValid, "type = \"box\"", "type = \"sphere\""), {"wall[0].type = \"sphere\"", "\"polygon\", \"box\""}},
      {"degenerate polygon", replace(kValid, "type = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.02, 0.02, 0.05]",
                                     "type = \"polygon\"\nvertices = [[0.0,0.0,0.0],[1.0,0.0,0.0],[2.0,0.0,0.0]]"),
       {"wall[0].vertices", "collinear"}},
      {"non-planar quad", replace(kValid, "type = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.02, 0.02, 0.05]",
                                  "type = \"polygon\"\nvertices = [[0,0,0],[1,0,0],[1,1,0.5],[0,1,0]]"),
       {"wall[0].vertices", "not in one plane"}},
      {"box max below min", replace(kValid, "max = [0.02, 0.02, 0.05]\n\n[generation]", "max = [0.02, -0.02, 0.05]\n\n[generation]"),
       {"wall[0].max", "must exceed min"}},
      {"Rmin > Rmax", replace(kValid, "radius_min = 0.001", "radius_min = 0.003"),
       {"generation.radius_max = 0.002", "radius_max must be >= radius_min"}},
      {"sphere larger than box", replace(kValid, "radius_max = 0.002", "radius_max = 0.02"),
       {"generation.radius_max = 0.02", "does not fit"}},
      {"placed sphere outside the box",
       replace(kValid, "materials = { glass = 1.0 }",
               "materials = { glass = 1.0 }\n[[generation.place]]\ncentre = [0.01, 0.01, 0.001]\nradius = 0.003\nmaterial = \"glass\""),
       {"generation.place[0].centre", "inside the generation box"}},
      {"placed spheres overlapping",
       replace(kValid, "materials = { glass = 1.0 }",
               "materials = { glass = 1.0 }\n[[generation.place]]\ncentre = [0.01, 0.01, 0.01]\nradius = 0.003\nmaterial = \"glass\""
               "\n[[generation.place]]\ncentre = [0.01, 0.01, 0.015]\nradius = 0.003\nmaterial = \"glass\""),
       {"generation.place[1].centre", "overlaps generation.place[0]"}},
      {"placed sphere of an unknown material",
       replace(kValid, "materials = { glass = 1.0 }",
               "materials = { glass = 1.0 }\n[[generation.place]]\ncentre = [0.01, 0.01, 0.01]\nradius = 0.003\nmaterial = \"lead\""),
       {"generation.place[0].material = \"lead\"", "no material of that name"}},
      {"count zero", replace(kValid, "count = 100", "count = 0"), {"generation.count = 0", "no spheres"}},
      {"count not an integer", replace(kValid, "count = 100", "count = 100.5"), {"generation.count = 100.5", "expected an integer"}},
      {"fractions do not sum to 1", replace(kValid, "materials = { glass = 1.0 }", "materials = { glass = 0.5 }"),
       {"generation.materials", "sum to 1"}},
      {"fraction for an unknown material", replace(kValid, "materials = { glass = 1.0 }", "materials = { glas = 1.0 }"),
       {"generation.materials.glas", "no material of that name"}},
      {"missing required key", replace(kValid, "count = 100\n", ""), {"generation.count is missing"}},
      {"gravity not a vector", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = -9.81"),
       {"simulation.gravity = -9.81", "array of 3 numbers"}},
      {"negative time step", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\ntime_step = -1e-6"),
       {"simulation.time_step", "out of range"}},
      {"frac above one", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nfrac = 2.0"),
       {"simulation.frac = 2", "(0, 1]"}},
      {"frac above 0.2, not forced", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nfrac = 0.9"),
       {"scene.toml:3:8: simulation.frac = 0.9", "above 0.2", "results are wrong", "simulation.force_time_step = true"}},
      {"negative duration", replace(kValid, "duration = 0.1", "duration = -0.1"), {"stage[0].duration = -0.1", "out of range", " s"}},
      {"motion of an unknown wall", replace(kValid, "wall = \"box\"", "wall = \"lid\""),
       {"stage[0].motion[0].wall = \"lid\"", "no wall or wall group"}},
      {"both amplitude and acceleration", replace(kValid, "acceleration = 29.43", "acceleration = 29.43\namplitude = 0.001"),
       {"stage[0].motion[0]", "exactly one of amplitude"}},
      {"zero vibration direction", replace(kValid, "direction = [0.0, 0.0, 1.0]", "direction = [0.0, 0.0, 0.0]"),
       {"stage[0].motion[0].direction", "non-zero"}},
      {"energy_every zero", replace(kValid, "duration = 0.1", "duration = 0.1\nenergy_every = 0.0"),
       {"stage[0].energy_every = 0", "(0,", "absent = no energy log"}},
      {"energy_every negative", replace(kValid, "duration = 0.1", "duration = 0.1\nenergy_every = -0.01"),
       {"stage[0].energy_every = -0.01", "(0,"}},
      {"energy_every a string", replace(kValid, "duration = 0.1", "duration = 0.1\nenergy_every = \"often\""),
       {"stage[0].energy_every"}},
      {"duplicate stage", kValid + "\n[[stage]]\nname = \"shake\"\nduration = 1.0\n", {"stage[1].name = \"shake\"", "duplicate stage"}},
      {"unknown action", kValid + "\n[[stage.action]]\ntype = \"explode\"\n", {"stage[0].action[0].type = \"explode\"", "\"remove\""}},
      {"max_overlap zero", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nmax_overlap = 0.0"),
       {"simulation.max_overlap = 0", "(0, 2]"}},
      {"max_energy_gain negative", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nmax_energy_gain = -1.0"),
       {"simulation.max_energy_gain = -1", "[0,", "0 = no check"}},
      {"negative skin", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nskin = -0.001"),
       {"simulation.skin = -0.001", "[0, inf) m"}},
      {"unknown law in a pair", replace(kValid, "[[wall]]", "[[pair]]\nmaterials = [\"glass\", \"glass\"]\nlaw = \"hooke\"\n\n[[wall]]"),
       {"pair[0].law = \"hooke\"", "\"cundall\", \"liu\", \"mendes\""}},
      {"pair with an unknown material", replace(kValid, "[[wall]]", "[[pair]]\nmaterials = [\"glass\", \"sand\"]\n\n[[wall]]"),
       {"pair[0].materials", "no material named \"sand\""}},
      {"epsilon out of range", replace(kValid, "density = 2500.0", "density = 2500.0\nlaw = \"mendes\"\nepsilon = 1.0"),
       {"material[0].epsilon = 1", "(0, 1)"}},
      {"negative tensile strength", replace(kValid, "density = 2500.0", "density = 2500.0\nlaw = \"liu\"\ntensile_strength = -1.0"),
       {"material[0].tensile_strength = -1", "[0, inf) N"}},
      {"hertz without its modulus", replace(kValid, "kn = 5.0e4", "law = \"hertz\"\npoisson_ratio = 0.3\nkt = 5.0e4"),
       {"material[0].young_modulus is missing (required)"}},
      {"kn on a hertz material", replace(kValid, "kn = 5.0e4", "law = \"hertz\"\nyoung_modulus = 1e7\npoisson_ratio = 0.3\nkn = 5.0e4"),
       {"material[0].kn = 50000", "a property of law = \"cundall\", law = \"liu\", law = \"mendes\", not of these laws"}},
      {"poisson ratio of 0.5", replace(kValid, "kn = 5.0e4", "law = \"hertz\"\nyoung_modulus = 1e7\npoisson_ratio = 0.5\nkt = 5.0e4"),
       {"material[0].poisson_ratio = 0.5", "(-1, 0.5)"}},
      {"a hertz pair with a cundall material",
       replace(replace(kValid, "[[wall]]", "[[material]]\nname = \"rubber\"\nlaw = \"hertz\"\ndensity = 1100.0\nyoung_modulus = 1e7\n"
                                          "poisson_ratio = 0.45\nkt = 1e4\n\n[[pair]]\nmaterials = [\"glass\", \"rubber\"]\n"
                                          "law = \"hertz\"\n\n[[wall]]"),
               "restitution = 0.3", "restitution = 1.0"),
       {"pair[0].materials", "the pair's laws (law = \"hertz\", tangential = \"coulomb\", rolling = \"none\") read young_modulus of "
                            "each material, and material \"glass\" (law = \"cundall\", tangential = \"coulomb\", rolling = \"none\") has none"}},
      {"mindlin without its modulus", replace(kValid, "kn = 5.0e4", "kn = 5.0e4\ntangential = \"mindlin\"\npoisson_ratio = 0.3"),
       {"material[0].young_modulus is missing (required)"}},
      {"kt on a mindlin material",
       replace(kValid, "kn = 5.0e4", "kn = 5.0e4\ntangential = \"mindlin\"\nyoung_modulus = 1e7\npoisson_ratio = 0.3\nkt = 1e4"),
       {"material[0].kt = 10000", "a property of tangential = \"coulomb\", not of these laws (law = \"cundall\", tangential = \"mindlin\", rolling = \"none\")"}},
      {"rolling without its coefficient", replace(kValid, "kn = 5.0e4", "kn = 5.0e4\nrolling = \"cdt\""),
       {"material[0].rolling_friction is missing (required)"}},
      {"rolling coefficient without a rolling law", replace(kValid, "kn = 5.0e4", "kn = 5.0e4\nrolling_friction = 0.1"),
       {"material[0].rolling_friction = 0.1", "a property of rolling = \"cdt\", rolling = \"epsd2\""}},
      {"unknown rolling law", replace(kValid, "kn = 5.0e4", "kn = 5.0e4\nrolling = \"epsd\""),
       {"material[0].rolling = \"epsd\"", "\"none\", \"cdt\", \"epsd2\""}},
      {"unknown tangential law", replace(kValid, "kn = 5.0e4", "kn = 5.0e4\ntangential = \"history\""),
       {"material[0].tangential = \"history\"", "\"coulomb\", \"mindlin\""}},
      {"unlike tangential laws without a pair",
       replace(kValid, "[[wall]]", "[[material]]\nname = \"steel\"\ndensity = 7800.0\nkn = 1e5\ntangential = \"mindlin\"\n"
                                  "young_modulus = 2e11\npoisson_ratio = 0.3\n\n[[wall]]"),
       {"materials \"glass\" and \"steel\" use different tangential laws", "tangential = \"...\" (allowed \"coulomb\", \"mindlin\")"}},
      {"a key only another law reads", replace(kValid, "density = 2500.0", "density = 2500.0\nepsilon = 0.01"),
       {"material[0].epsilon = 0.01", "a property of law = \"mendes\", not of these laws (law = \"cundall\", tangential = \"coulomb\", rolling = \"none\")"}},
      {"a pair key only another law reads",
       replace(kValid, "[[wall]]", "[[pair]]\nmaterials = [\"glass\", \"glass\"]\ntensile_strength = 5.0\n\n[[wall]]"),
       {"pair[0].tensile_strength = 5", "a property of law = \"liu\", law = \"mendes\""}},
      {"bond action with a region", kValid + "\n[[stage.action]]\ntype = \"bond\"\nregion = { type = \"box\", min = [0,0,0], max = [1,1,1] }\n",
       {"stage[0].action[0].region", "unknown key"}},
      {"boolean expected", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nforce_time_step = 1"),
       {"simulation.force_time_step = 1", "expected true or false"}},
      {"explicit_dashpot not a boolean", replace(kValid, "density = 2500.0", "density = 2500.0\nexplicit_dashpot = 1"),
       {"material[0].explicit_dashpot = 1", "expected true or false"}},
      {"table not starting at 0", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"table\"\ntable = [[0.1, 0, 0, 0], [0.2, 0, 0, 1]]\n",
       {"stage[0].motion[1].table", "first row must be at t = 0"}},
      {"table times not increasing", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"table\"\ntable = [[0, 0, 0, 0], [0.2, 0, 0, 1], [0.2, 0, 0, 2]]\n",
       {"stage[0].motion[1].table", "increase strictly"}},
      {"table row of 3", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"table\"\ntable = [[0, 0, 0], [0.2, 0, 0]]\n",
       {"stage[0].motion[1].table", "expected a row [t, x, y, z]"}},
      {"rotation at 0 rpm", kValid + "\n[[stage.motion]]\nwall = \"box\"\ntype = \"rotate\"\naxis = [0, 0, 1]\ncentre = [0, 0, 0]\nrpm = 0\n",
       {"stage[0].motion[1].rpm = 0", "non-zero speed"}},
      {"rotation about a zero axis", kValid + "\n[[stage.motion]]\nwall = \"box\"\ntype = \"rotate\"\naxis = [0, 0, 0]\ncentre = [0, 0, 0]\nrpm = 10\n",
       {"stage[0].motion[1].axis", "non-zero"}},
      {"servo on a vibrating wall", kValid + "\n[[stage.servo]]\nwall = \"box.zmax\"\ntarget_stress = 1000.0\nmax_speed = 0.1\n",
       {"stage[0].servo[0].wall = \"box.zmax\"", "also moves by [[stage.motion]]"}},
      {"servo with negative stress", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"fixed\"\n[[stage.servo]]\nwall = \"box.zmax\"\ntarget_stress = -1000.0\nmax_speed = 0.1\n",
       {"stage[0].servo[0].target_stress = -1000", "(0, inf) Pa"}},
      {"servo gain above one", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"fixed\"\n[[stage.servo]]\nwall = \"box.zmax\"\ntarget_stress = 1000.0\nmax_speed = 0.1\ngain = 2.0\n",
       {"stage[0].servo[0].gain = 2", "(0, 1]"}},
      {"servo integral_time negative", kValid + "\n[[stage.motion]]\nwall = \"box.zmax\"\ntype = \"fixed\"\n[[stage.servo]]\nwall = \"box.zmax\"\ntarget_stress = 1000.0\nmax_speed = 0.1\nintegral_time = -0.01\n",
       {"stage[0].servo[0].integral_time = -0.01", "[0,"}},
      {"servo of an unknown wall", kValid + "\n[[stage.servo]]\nwall = \"lid\"\ntarget_stress = 1000.0\nmax_speed = 0.1\n",
       {"stage[0].servo[0].wall = \"lid\"", "no wall or wall group"}},
      // Cutting regions (stage action remove, [[generation.cut]]).
      {"unknown region type", kValid + remove_region("{ type = \"cone\", centre = [0, 0, 0] }"),
       {"stage[0].action[0].region.type = \"cone\"", "allowed \"box\", \"sphere\", \"cylinder\", \"half_space\", \"mesh\""}},
      {"cylinder of negative radius", kValid + remove_region("{ type = \"cylinder\", centre = [0, 0, 0], radius = -0.1 }"),
       {"stage[0].action[0].region.radius = -0.1", "out of range: allowed (0, inf) m"}},
      {"cylinder of zero length", kValid + remove_region("{ type = \"cylinder\", centre = [0, 0, 0], radius = 0.1, length = 0 }"),
       {"stage[0].action[0].region.length = 0", "allowed (0, inf) m (omit for an infinite cylinder)"}},
      {"cylinder about a zero axis", kValid + remove_region("{ type = \"cylinder\", centre = [0, 0, 0], radius = 0.1, axis = [0, 0, 0] }"),
       {"stage[0].action[0].region.axis", "non-zero"}},
      {"cylinder without centre", kValid + remove_region("{ type = \"cylinder\", radius = 0.1 }"),
       {"stage[0].action[0].region.centre is missing"}},
      {"cylinder with a box key", kValid + remove_region("{ type = \"cylinder\", centre = [0, 0, 0], radius = 0.1, height = 1 }"),
       {"stage[0].action[0].region.height = 1", "unknown key", "allowed here: axis, centre, length, radius, type"}},
      {"half-space of zero normal", kValid + remove_region("{ type = \"half_space\", point = [0, 0, 0], normal = [0, 0, 0] }"),
       {"stage[0].action[0].region.normal", "non-zero"}},
      {"half-space without point", kValid + remove_region("{ type = \"half_space\", normal = [0, 0, 1] }"),
       {"stage[0].action[0].region.point is missing"}},
      {"mesh region, missing file", kValid + remove_region("{ type = \"mesh\", file = \"no_such.stl\" }"),
       {"stage[0].action[0].region.file = \"no_such.stl\"", "cannot open the STL file"}},
      {"mesh region, open surface", kValid + remove_region("{ type = \"mesh\", file = \"" DEM_TEST_DATA "/baffle.stl\" }"),
       {"stage[0].action[0].region.file", "the mesh is not closed: 4 edges belong to one triangle only"}},
      {"mesh region, inconsistent orientation",
       kValid + remove_region("{ type = \"mesh\", file = \"" DEM_TEST_DATA "/cube_flipped.stl\", scale = 0.001 }"),
       {"stage[0].action[0].region.file", "not consistently oriented", "between (0, 0, 0) and (0, 0, 0.01)"}},
      {"mesh region, zero scale", kValid + remove_region("{ type = \"mesh\", file = \"" DEM_TEST_DATA "/cube.stl\", scale = 0 }"),
       {"stage[0].action[0].region.scale = 0", "(0, inf)"}},
      {"cut without region", replace(kValid, "[[stage]]", "[[generation.cut]]\ninside = false\n\n[[stage]]"),
       {"generation.cut[0].region is missing"}},
      {"cut with inside = 1", replace(kValid, "[[stage]]", "[[generation.cut]]\nregion = { type = \"sphere\", centre = [0, 0, 0], radius = 0.01 }\ninside = 1\n\n[[stage]]"),
       {"generation.cut[0].inside = 1", "expected true or false"}},
      {"cut with an unknown key", replace(kValid, "[[stage]]", "[[generation.cut]]\nregion = { type = \"sphere\", centre = [0, 0, 0], radius = 0.01 }\noutside = true\n\n[[stage]]"),
       {"generation.cut[0].outside = true", "unknown key", "allowed here: inside, region"}},
      {"cut with a bad region", replace(kValid, "[[stage]]", "[[generation.cut]]\nregion = { type = \"half_space\", point = [0, 0, 0], normal = [0, 0] }\n\n[[stage]]"),
       {"generation.cut[0].region.normal", "array of 3 numbers"}},
      {"periodic period reversed", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nperiodic = { x = [0.02, 0.0] }"),
       {"scene.toml:3", "simulation.periodic.x = [...]", "hi must exceed lo"}},
      {"periodic period of one number", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nperiodic = { y = 0.02 }"),
       {"simulation.periodic.y = 0.02", "expected [lo, hi] in m"}},
      {"periodic with no axis", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nperiodic = {}"),
       {"simulation.periodic = {...}", "at least one axis"}},
      {"periodic with an unknown axis", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nperiodic = { w = [0.0, 0.02] }"),
       {"simulation.periodic.w", "unknown key", "allowed here: x, y, z"}},
      {"generation box beyond the period",
       replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nperiodic = { x = [0.0, 0.01] }"),
       {"generation.box_max", "along the periodic axis x", "within simulation.periodic"}},
      {"sort_every negative", replace(kValid, "gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]\nsort_every = -1"),
       {"simulation.sort_every = -1", "out of range: allowed [0, 1000000000]"}},
      {"fix without region", kValid + "\n[[stage.action]]\ntype = \"fix\"\n", {"stage[0].action[0].region is missing"}},
      {"release with a bad inside", kValid + "\n[[stage.action]]\ntype = \"release\"\ninside = \"yes\"\n",
       {"stage[0].action[0].inside = \"yes\"", "expected true or false"}},
  };
}

INSTANTIATE_TEST_SUITE_P(BadInputs, SceneRejects, ::testing::ValuesIn(bad_cases()));

// Implausible values (docs/scene.md, "Warnings") are accepted with a warning that names the place,
// the value and the likely unit; a plausible scene has none.
struct WarnCase {
  const char* what;
  std::string text;
  std::vector<std::string> expect;  // fragments of the one warning
};

TEST(SceneWarnings, PlausibleSceneHasNone) { EXPECT_TRUE(parse_scene(kValid, "scene.toml").warnings.empty()); }

TEST(SceneWarnings, ImplausibleValuesWarnWithTheLikelyUnit) {
  const std::string sim = "gravity = [0.0, 0.0, -9.81]";
  const std::vector<WarnCase> cases = {
      {"density in g/cm^3", replace(kValid, "density = 2500.0", "density = 2.5"),
       {"scene.toml:6:11: material[0].density = 2.5", "density 2.5 kg/m^3", "is it in g/cm^3? (kg/m^3 expected"}},
      {"density too high", replace(kValid, "density = 2500.0", "density = 2.5e6"), {"material[0].density", "denser than any solid"}},
      {"kn in kN/m", replace(kValid, "kn = 5.0e4", "kn = 0.05"), {"material[0].kn = 0.05", "is it in kN/m"}},
      {"E in GPa", replace(kValid, "kn = 5.0e4", "law = \"hertz\"\nyoung_modulus = 70.0\npoisson_ratio = 0.25\nkt = 4.0e4"),
       {"material[0].young_modulus = 70", "is it in GPa"}},
      {"gravity in mm/s^2", replace(kValid, sim, "gravity = [0.0, 0.0, -9810.0]"), {"simulation.gravity", "|g| = 9810", "mm/s^2"}},
      {"gravity in g", replace(kValid, sim, "gravity = [0.0, 0.0, -1.0e-3]"), {"simulation.gravity", "units of g"}},
      {"walls in mm", replace(kValid, "max = [0.02, 0.02, 0.05]", "max = [20.0, 20.0, 500.0]"),
       {"wall[0].type = \"box\"", "spans 500 m", "lengths in mm? (m expected)"}},
      {"generation box in mm", replace(replace(kValid, "box_max = [0.02, 0.02, 0.05]", "box_max = [20.0, 20.0, 500.0]"), "radius_max = 0.002",
                                       "radius_max = 0.002"),
       {"generation.box_max", "the generation box spans 500 m", "lengths in mm?"}},
      {"radii in mm", replace(replace(replace(kValid, "box_max = [0.02, 0.02, 0.05]", "box_max = [20.0, 20.0, 50.0]"), "radius_max = 0.002", "radius_max = 2.0"),
                              "max = [0.02, 0.02, 0.05]", "max = [20.0, 20.0, 50.0]"),
       {"generation.radius_max = 2", "radius up to 2 m", "lengths in mm?"}},
      {"amplitude in mm", replace(kValid, "acceleration = 29.43", "amplitude = 2.0"),
       {"stage[0].motion[0].amplitude = 2", "peak acceleration", "amplitude in mm? (m expected)"}},
      {"frac above 0.2, forced", replace(kValid, sim, sim + "\nfrac = 0.9\nforce_time_step = true"),
       {"simulation.frac = 0.9", "forced (simulation.force_time_step = true)", "results are wrong"}},
  };
  for (const WarnCase& c : cases) {
    const Scene sc = parse_scene(c.text, "scene.toml");
    bool found = false;
    for (const std::string& w : sc.warnings) {
      bool all = true;
      for (const std::string& f : c.expect) all = all && w.find(f) != std::string::npos;
      found = found || all;
    }
    std::string got;
    for (const std::string& w : sc.warnings) got += "\n  " + w;
    EXPECT_TRUE(found) << c.what << ": no warning with every fragment; warnings:" << got;
  }
}

// [[stage.insert]]: a valid group, then each malformed key rejected with its name and what is allowed.
const std::string kInsert = R"(
[[stage.insert]]
region = { type = "box", min = [0.0, 0.0, 0.03], max = [0.02, 0.02, 0.05] }
material = "glass"
radius_min = 0.001
radius_max = 0.0015
mass_rate = 0.5
velocity = [0.0, 0.0, -1.0]
seed = 9
)";

std::string with_insert(const std::string& from, const std::string& to) { return kValid + replace(kInsert, from, to); }

TEST(SceneParser, InsertParses) {
  const Scene s = parse_scene(kValid + kInsert, "scene.toml");
  ASSERT_EQ(s.stages[0].inserts.size(), 1u);
  const InsertSpec& g = s.stages[0].inserts[0];
  EXPECT_EQ(g.rate_kind, InsertSpec::Rate::Mass);
  EXPECT_EQ(g.rate, 0.5);
  EXPECT_EQ(g.velocity, Vec3(0, 0, -1));
  EXPECT_EQ(g.seed, 9u);
  EXPECT_EQ(g.start, 0);
  EXPECT_TRUE(std::isinf(g.end) && std::isinf(g.total)) << "the whole stage, no cap";
  EXPECT_EQ(g.every, 1);
  ASSERT_EQ(g.material_fractions.size(), 1u);
  const Scene sieve = parse_scene(kValid + replace(replace(kInsert, "radius_min = 0.001\nradius_max = 0.0015\n",
                                                           "size = { distribution = \"sieve\", sieve = [[0.002, 0.0], [0.003, 1.0]] }\n"),
                                                   "material = \"glass\"", "materials = { glass = 1.0 }"),
                                  "scene.toml");
  EXPECT_EQ(sieve.stages[0].inserts[0].radius_max, 0.0015) << "the sieve's largest diameter / 2";
}

std::vector<BadCase> insert_bad_cases() {
  return {
      {"insert: unknown key", with_insert("seed = 9", "seed = 9\nrat = 1.0"), {"stage[0].insert[0].rat", "unknown key", "allowed here"}},
      {"insert: no rate", with_insert("mass_rate = 0.5\n", ""), {"stage[0].insert[0].count_rate", "exactly one of count_rate [1/s] and mass_rate [kg/s]"}},
      {"insert: two rates", with_insert("mass_rate = 0.5", "mass_rate = 0.5\ncount_rate = 100.0"), {"insert[0].mass_rate = 0.5", "exactly one"}},
      {"insert: negative rate", with_insert("mass_rate = 0.5", "mass_rate = -0.5"), {"insert[0].mass_rate = -0.5", "out of range", "(0, inf) kg/s"}},
      {"insert: half-space region", with_insert("{ type = \"box\", min = [0.0, 0.0, 0.03], max = [0.02, 0.02, 0.05] }",
                                                "{ type = \"half_space\", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }"),
       {"insert[0].region", "bounded region", "a box, a sphere, a cylinder with a length, or a mesh"}},
      {"insert: sphere too large for the region", with_insert("radius_max = 0.0015", "radius_max = 0.015"),
       {"insert[0].region", "does not fit in the region"}},
      {"insert: radius_max below radius_min", with_insert("radius_max = 0.0015", "radius_max = 0.0005"), {"insert[0].radius_max = 0.0005", ">= radius_min"}},
      {"insert: unknown material", with_insert("material = \"glass\"", "material = \"sand\""),
       {"insert[0].material = \"sand\"", "no material of that name", "\"glass\""}},
      {"insert: material and materials", with_insert("material = \"glass\"", "material = \"glass\"\nmaterials = { glass = 1.0 }"),
       {"insert[0].materials", "exactly one of material"}},
      {"insert: fractions not summing to one", with_insert("material = \"glass\"", "materials = { glass = 0.5 }"),
       {"insert[0].materials", "sum to 1"}},
      {"insert: end before start", with_insert("seed = 9", "seed = 9\nstart = 0.05\nend = 0.01"), {"insert[0].end = 0.01", "after start"}},
      {"insert: start after the stage", with_insert("seed = 9", "seed = 9\nstart = 0.2"), {"insert[0].start = 0.2", "out of range", "[0, 0.1)"}},
      {"insert: total of the other kind", with_insert("seed = 9", "seed = 9\ntotal_count = 10"), {"insert[0].total_count = 10", "total_mass"}},
      {"insert: every zero", with_insert("seed = 9", "seed = 9\nevery = 0"), {"insert[0].every = 0", "[1, 1000000000]"}},
      {"insert: velocity not a vector", with_insert("velocity = [0.0, 0.0, -1.0]", "velocity = -1.0"),
       {"insert[0].velocity = -1", "array of 3 numbers"}},
      {"insert: sieve and radius bounds", with_insert("radius_min = 0.001", "size = { distribution = \"sieve\", sieve = [[0.002, 0.0], [0.003, 1.0]] }\nradius_min = 0.001"),
       {"insert[0].radius_min", "not used with size.distribution = \"sieve\""}},
  };
}

INSTANTIATE_TEST_SUITE_P(BadInsert, SceneRejects, ::testing::ValuesIn(insert_bad_cases()));

// [[stage.set_velocity]], [[stage.prescribe]] and the bond action's gap: valid entries, then each
// malformed key rejected with its name and what is allowed.
const std::string kVelocities = R"(
[[stage.action]]
type = "bond"
gap = 1e-4

[[stage.set_velocity]]
material = "glass"
velocity = [0.0, 0.0, -5.0]
angular_velocity = [0.0, 1.0, 0.0]

[[stage.prescribe]]
ids = [0, 9]
region = { type = "box", min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.01] }
inside = false
velocity = [0.001, 0.0, 0.0]
)";

std::string with_velocities(const std::string& from, const std::string& to) { return kValid + replace(kVelocities, from, to); }

TEST(SceneParser, VelocityGroupsAndBondGapParse) {
  const Scene s = parse_scene(kValid + kVelocities, "scene.toml");
  const StageSpec& st = s.stages[0];
  ASSERT_EQ(st.actions.size(), 1u);
  EXPECT_EQ(st.actions[0].gap, 1e-4);
  ASSERT_EQ(st.set_velocities.size(), 1u);
  EXPECT_EQ(st.set_velocities[0].group.material, 0);
  EXPECT_FALSE(st.set_velocities[0].group.by_ids);
  EXPECT_EQ(st.set_velocities[0].velocity, Vec3(0, 0, -5));
  EXPECT_EQ(st.set_velocities[0].angular_velocity, Vec3(0, 1, 0));
  ASSERT_EQ(st.prescribes.size(), 1u);
  const ParticleGroupSpec& g = st.prescribes[0].group;
  EXPECT_EQ(g.material, -1);
  EXPECT_TRUE(g.by_ids && g.id_first == 0 && g.id_last == 9);
  EXPECT_TRUE(g.region && !g.inside);
  EXPECT_FALSE(st.prescribes[0].angular_velocity) << "none given: zero spin";
  const Scene plain = parse_scene(kValid + "\n[[stage.action]]\ntype = \"bond\"\n", "scene.toml");
  EXPECT_EQ(plain.stages[0].actions[0].gap, 1e-6) << "the default: round-off of touching positions";
}

std::vector<BadCase> velocity_bad_cases() {
  return {
      {"set_velocity: no group", with_velocities("material = \"glass\"\nvelocity", "velocity"),
       {"stage[0].set_velocity[0].material", "give at least one of material", "ids = [first, last]", "region"}},
      {"set_velocity: unknown material", with_velocities("material = \"glass\"", "material = \"B2\""),
       {"stage[0].set_velocity[0].material = \"B2\"", "no material of that name", "\"glass\""}},
      {"set_velocity: no velocity", with_velocities("velocity = [0.0, 0.0, -5.0]\n", ""), {"stage[0].set_velocity[0].velocity is missing"}},
      {"set_velocity: velocity not a vector", with_velocities("velocity = [0.0, 0.0, -5.0]", "velocity = -5.0"),
       {"stage[0].set_velocity[0].velocity = -5", "array of 3 numbers"}},
      {"set_velocity: unknown key", with_velocities("angular_velocity", "spin = 1.0\nangular_velocity"),
       {"stage[0].set_velocity[0].spin", "unknown key", "allowed here"}},
      {"prescribe: ids of one", with_velocities("ids = [0, 9]", "ids = [3]"), {"stage[0].prescribe[0].ids", "two integers [first, last]"}},
      {"prescribe: ids reversed", with_velocities("ids = [0, 9]", "ids = [9, 0]"), {"stage[0].prescribe[0].ids", "0 <= first <= last"}},
      {"prescribe: ids not integers", with_velocities("ids = [0, 9]", "ids = [0.5, 9]"), {"stage[0].prescribe[0].ids", "two integers"}},
      {"prescribe: inside without region",
       with_velocities("region = { type = \"box\", min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.01] }\n", ""),
       {"stage[0].prescribe[0].inside = false", "give region too"}},
      {"prescribe: bad region", with_velocities("max = [0.02, 0.02, 0.01]", "max = [0.02, -0.02, 0.01]"),
       {"stage[0].prescribe[0].region"}},
      {"bond: negative gap", with_velocities("gap = 1e-4", "gap = -1e-4"), {"stage[0].action[0].gap = -0.0001", "out of range", "[0, 1)"}},
      {"bond: gap of a radius", with_velocities("gap = 1e-4", "gap = 1.0"), {"stage[0].action[0].gap = 1", "fraction of the smaller radius"}},
  };
}

INSTANTIATE_TEST_SUITE_P(BadVelocity, SceneRejects, ::testing::ValuesIn(velocity_bad_cases()));

// [stage.fluid]: a uniform flow and a well parse; each malformed key is rejected with its name,
// value and what is allowed.
const std::string kUniformFluid = R"(
[stage.fluid]
flow = "uniform"
viscosity = 1.0e-3
density = 998.0
void_cutoff = 0.003
void_every = 20
pressure_gradient = [0.0, 0.0, -1.0e4]
)";
const std::string kWellFluid = R"(
[stage.fluid]
flow = "well"
viscosity = 5.0e-3
density = 850.0
void_cutoff = 0.03
well_centre = [0.5, 0.5, 0.0]
well_axis = [0.0, 0.0, 2.0]
well_radius = 0.09
drainage_radius = 200.0
drawdown = 15.0e6
)";

std::string with_fluid(const std::string& fluid, const std::string& from, const std::string& to) { return kValid + replace(fluid, from, to); }

TEST(SceneParser, FluidParses) {
  const Scene u = parse_scene(kValid + kUniformFluid, "scene.toml");
  ASSERT_TRUE(u.stages[0].fluid);
  const FluidParams& f = *u.stages[0].fluid;
  EXPECT_EQ(f.flow, FluidParams::Flow::Uniform);
  EXPECT_EQ(f.viscosity, 1.0e-3);
  EXPECT_EQ(f.density, 998.0);
  EXPECT_EQ(f.void_cutoff, 0.003);
  EXPECT_EQ(f.void_every, 20);
  EXPECT_EQ(f.gradient, Vec3(0, 0, -1e4));
  const Scene w = parse_scene(kValid + kWellFluid, "scene.toml");
  const FluidParams& g = *w.stages[0].fluid;
  EXPECT_EQ(g.flow, FluidParams::Flow::Well);
  EXPECT_EQ(g.well_axis, Vec3(0, 0, 1)) << "normalised";
  EXPECT_EQ(g.void_every, 100) << "the default";
  EXPECT_EQ(g.drainage_radius, 200.0);
  EXPECT_EQ(g.drawdown, 15e6);
  EXPECT_FALSE(parse_scene(kValid, "scene.toml").stages[0].fluid) << "no fluid unless asked";
  const Scene typo = parse_scene(kValid + replace(kUniformFluid, "viscosity = 1.0e-3", "viscosity = 13.5e2"), "scene.toml");
  ASSERT_EQ(typo.warnings.size(), 1u) << "a viscosity of 1350 Pa s is warned about";
  EXPECT_NE(typo.warnings[0].find("stage[0].fluid.viscosity"), std::string::npos) << typo.warnings[0];
}

std::vector<BadCase> fluid_bad_cases() {
  return {
      {"fluid: array of tables", kValid + replace(kUniformFluid, "[stage.fluid]", "[[stage.fluid]]"), {"stage[0].fluid", "expected a table"}},
      {"fluid: no flow", with_fluid(kUniformFluid, "flow = \"uniform\"\n", ""), {"stage[0].fluid.flow is missing"}},
      {"fluid: unknown flow", with_fluid(kUniformFluid, "flow = \"uniform\"", "flow = \"darcy\""), {"stage[0].fluid.flow = \"darcy\"", "\"uniform\"", "\"well\""}},
      {"fluid: zero viscosity", with_fluid(kUniformFluid, "viscosity = 1.0e-3", "viscosity = 0.0"), {"stage[0].fluid.viscosity = 0", "out of range", "(0, inf)", "Pa s"}},
      {"fluid: no viscosity", with_fluid(kUniformFluid, "viscosity = 1.0e-3\n", ""), {"stage[0].fluid.viscosity is missing"}},
      {"fluid: negative density", with_fluid(kUniformFluid, "density = 998.0", "density = -1.0"), {"stage[0].fluid.density = -1", "kg/m^3"}},
      {"fluid: no void_cutoff", with_fluid(kUniformFluid, "void_cutoff = 0.003\n", ""), {"stage[0].fluid.void_cutoff is missing"}},
      {"fluid: zero void_cutoff", with_fluid(kUniformFluid, "void_cutoff = 0.003", "void_cutoff = 0.0"), {"stage[0].fluid.void_cutoff = 0", "(0, inf)"}},
      {"fluid: void_every zero", with_fluid(kUniformFluid, "void_every = 20", "void_every = 0"), {"stage[0].fluid.void_every = 0", "[1, 1000000000]"}},
      {"fluid: void_every fractional", with_fluid(kUniformFluid, "void_every = 20", "void_every = 2.5"), {"stage[0].fluid.void_every", "integer"}},
      {"fluid: uniform without gradient", with_fluid(kUniformFluid, "pressure_gradient = [0.0, 0.0, -1.0e4]\n", ""),
       {"stage[0].fluid.pressure_gradient is missing"}},
      {"fluid: gradient of two numbers", with_fluid(kUniformFluid, "[0.0, 0.0, -1.0e4]", "[0.0, -1.0e4]"), {"stage[0].fluid.pressure_gradient", "array of 3 numbers"}},
      {"fluid: uniform with a well key", with_fluid(kUniformFluid, "void_every = 20", "void_every = 20\nwell_radius = 0.09"),
       {"stage[0].fluid.well_radius", "belongs to flow = \"well\""}},
      {"fluid: well with a gradient", with_fluid(kWellFluid, "drawdown = 15.0e6", "drawdown = 15.0e6\npressure_gradient = [0.0, 0.0, 1.0]"),
       {"stage[0].fluid.pressure_gradient", "belongs to flow = \"uniform\""}},
      {"fluid: well without centre", with_fluid(kWellFluid, "well_centre = [0.5, 0.5, 0.0]\n", ""), {"stage[0].fluid.well_centre is missing"}},
      {"fluid: zero well axis", with_fluid(kWellFluid, "well_axis = [0.0, 0.0, 2.0]", "well_axis = [0.0, 0.0, 0.0]"), {"stage[0].fluid.well_axis", "non-zero vector"}},
      {"fluid: zero well radius", with_fluid(kWellFluid, "well_radius = 0.09", "well_radius = 0.0"), {"stage[0].fluid.well_radius = 0", "(0, inf)"}},
      {"fluid: drainage inside the well", with_fluid(kWellFluid, "drainage_radius = 200.0", "drainage_radius = 0.05"),
       {"stage[0].fluid.drainage_radius = 0.05", "must exceed well_radius (0.09 m)"}},
      {"fluid: no drawdown", with_fluid(kWellFluid, "drawdown = 15.0e6\n", ""), {"stage[0].fluid.drawdown is missing"}},
      {"fluid: drawdown not a number", with_fluid(kWellFluid, "drawdown = 15.0e6", "drawdown = \"15 MPa\""), {"stage[0].fluid.drawdown", "expected a number"}},
      {"fluid: unknown key", with_fluid(kUniformFluid, "void_every = 20", "void_every = 20\npermeability = 1.8e-10"),
       {"stage[0].fluid.permeability", "unknown key", "allowed here"}},
  };
}

INSTANTIATE_TEST_SUITE_P(BadFluid, SceneRejects, ::testing::ValuesIn(fluid_bad_cases()));
// [stage.fibres]: a valid table, then each malformed key rejected with its name and what is allowed.
const std::string kFibres = R"(
[stage.fibres]
volume_fraction = 0.005
length = 0.012
diameter = 1.0e-4
youngs_modulus = 3.0e9
tensile_strength = 3.0e8
seed = 7
)";

std::string with_fibres(const std::string& from, const std::string& to) { return kValid + replace(kFibres, from, to); }

TEST(SceneParser, FibresParse) {
  const Scene s = parse_scene(kValid + kFibres, "scene.toml");
  ASSERT_TRUE(s.stages[0].fibres);
  const FibreSpec& f = *s.stages[0].fibres;
  EXPECT_EQ(f.count, 0);
  EXPECT_EQ(f.volume_fraction, 0.005);
  EXPECT_EQ(f.length_min, 0.012);
  EXPECT_EQ(f.length_max, 0.012);
  EXPECT_EQ(f.diameter, 1e-4);
  EXPECT_EQ(f.youngs_modulus, 3e9);
  EXPECT_EQ(f.tensile_strength, 3e8);
  EXPECT_EQ(f.seed, 7u);
  const Scene r = parse_scene(with_fibres("volume_fraction = 0.005\nlength = 0.012", "count = 20\nlength_min = 0.01\nlength_max = 0.02"), "scene.toml");
  EXPECT_EQ(r.stages[0].fibres->count, 20);
  EXPECT_EQ(r.stages[0].fibres->length_min, 0.01);
  EXPECT_EQ(r.stages[0].fibres->length_max, 0.02);
  EXPECT_FALSE(parse_scene(kValid, "scene.toml").stages[0].fibres);
}

std::vector<BadCase> fibre_bad_cases() {
  return {
      {"fibres: count and fraction", with_fibres("seed = 7", "seed = 7\ncount = 3"), {"stage[0].fibres.count", "exactly one of count"}},
      {"fibres: neither count nor fraction", with_fibres("volume_fraction = 0.005\n", ""), {"stage[0].fibres.count", "exactly one of count"}},
      {"fibres: count zero", with_fibres("volume_fraction = 0.005", "count = 0"), {"stage[0].fibres.count = 0", "out of range"}},
      {"fibres: fraction above half", with_fibres("volume_fraction = 0.005", "volume_fraction = 0.7"),
       {"stage[0].fibres.volume_fraction = 0.7", "out of range", "(0, 0.5]"}},
      {"fibres: no length", with_fibres("length = 0.012\n", ""), {"stage[0].fibres.length", "either length"}},
      {"fibres: length and bounds", with_fibres("length = 0.012", "length = 0.012\nlength_min = 0.01"), {"stage[0].fibres.length", "either length"}},
      {"fibres: bounds reversed", with_fibres("length = 0.012", "length_min = 0.02\nlength_max = 0.01"),
       {"stage[0].fibres.length_max = 0.01", "out of range"}},
      {"fibres: only length_min", with_fibres("length = 0.012", "length_min = 0.02"), {"stage[0].fibres.length_max is missing"}},
      {"fibres: negative length", with_fibres("length = 0.012", "length = -0.012"), {"stage[0].fibres.length = -0.012", "out of range"}},
      {"fibres: zero diameter", with_fibres("diameter = 1.0e-4", "diameter = 0.0"), {"stage[0].fibres.diameter = 0", "out of range", "m"}},
      {"fibres: no diameter", with_fibres("diameter = 1.0e-4\n", ""), {"stage[0].fibres.diameter is missing"}},
      {"fibres: negative modulus", with_fibres("youngs_modulus = 3.0e9", "youngs_modulus = -3.0e9"),
       {"stage[0].fibres.youngs_modulus", "out of range", "Pa"}},
      {"fibres: zero strength", with_fibres("tensile_strength = 3.0e8", "tensile_strength = 0.0"),
       {"stage[0].fibres.tensile_strength = 0", "out of range", "Pa"}},
      {"fibres: negative seed", with_fibres("seed = 7", "seed = -7"), {"stage[0].fibres.seed = -7", "out of range"}},
      {"fibres: unknown key", with_fibres("seed = 7", "seed = 7\nstrength = 1.0"), {"stage[0].fibres.strength", "unknown key"}},
  };
}

INSTANTIATE_TEST_SUITE_P(BadFibres, SceneRejects, ::testing::ValuesIn(fibre_bad_cases()));

// run-stage --restart accepts a scene file edited since the periodic checkpoint only where it holds
// the same values (stage_runner.cpp, check_resumable).
TEST(SceneParser, SameValuesIgnoreCommentsLayoutKeyOrderAndNumberSpelling) {
  const std::string a = "[simulation]\nfrac = 0.1\nsteps = 3\n[[stage]]\nname = \"a\"\nduration = 1e-3\n";
  EXPECT_TRUE(same_scene_values(a, a));
  EXPECT_TRUE(same_scene_values(a, "# a note\n[simulation]  # the run\nsteps   =   3\nfrac = 0.10\n\n[[stage]]\nname = \"a\"\nduration = 1.0e-3\n"));
  EXPECT_FALSE(same_scene_values(a, "[simulation]\nfrac = 0.2\nsteps = 3\n[[stage]]\nname = \"a\"\nduration = 1e-3\n")) << "a value";
  EXPECT_FALSE(same_scene_values(a, "[simulation]\nfrac = 0.1\nsteps = 3.0\n[[stage]]\nname = \"a\"\nduration = 1e-3\n")) << "a type";
  EXPECT_FALSE(same_scene_values(a, "[simulation]\nfrac = 0.1\nsteps = 3\n[[stage]]\nname = \"a\"\nduration = 1e-3\nextra = 0\n")) << "a key";
  EXPECT_FALSE(same_scene_values("g = [0.0, 0.0]\n", "g = [0.0, -0.0]\n")) << "the sign of a zero";
  EXPECT_FALSE(same_scene_values("[[s]]\nn = 1\n[[s]]\nn = 2\n", "[[s]]\nn = 2\n[[s]]\nn = 1\n")) << "the order of stages";
  EXPECT_FALSE(same_scene_values(a, "[simulation\n")) << "a text that does not parse";
}

}  // namespace
}  // namespace dem
