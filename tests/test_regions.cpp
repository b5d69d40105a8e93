// Cutting regions (SPEC §9 step 4): each region's inside test against the analytic answer for
// random points (cylinder: distance to the axis and position along it; half-space: the sign of a
// dot product; mesh: a closed cube read from STL, a hollow cube and a sphere-like icosphere), the
// rejection of meshes that are not closed, and the scene syntax of the new regions.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/scene_parser.hpp"
#include "io/stl.hpp"
#include "scene/region.hpp"

namespace dem {
namespace {

using Tri = std::array<Vec3, 3>;

Vec3 random_point(std::mt19937_64& rng, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  return Vec3(u(rng), u(rng), u(rng));
}

TEST(Region, CylinderFiniteAndInfinite) {
  std::mt19937_64 rng(11);
  Region g;
  g.kind = Region::Kind::Cylinder;
  g.centre = Vec3(0.1, -0.2, 0.05);
  g.axis = Vec3(1, 2, 2).normalized();
  g.radius = 0.3;
  int in_finite = 0, in_infinite = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 x = g.centre + random_point(rng, 1.0);
    // Analytic: distance to the axis line by the cross product, position along it by the dot product.
    const Vec3 d = x - g.centre;
    const double to_axis = d.cross(g.axis).norm(), along = d.dot(g.axis);
    g.length = 0;  // infinite
    const bool want_inf = to_axis <= g.radius;
    EXPECT_EQ(g.contains(x), want_inf) << x.transpose();
    g.length = 0.8;
    const bool want_fin = want_inf && std::abs(along) <= 0.4;
    EXPECT_EQ(g.contains(x), want_fin) << x.transpose();
    in_infinite += want_inf, in_finite += want_fin;
  }
  // Both answers occur often enough to mean something (volume fractions about 0.1 and 0.03).
  EXPECT_GT(in_infinite, 1000);
  EXPECT_GT(in_finite, 300);
  EXPECT_LT(in_finite, in_infinite);
}

TEST(Region, HalfSpaceIsTheSideTheNormalPointsInto) {
  std::mt19937_64 rng(12);
  Region g;
  g.kind = Region::Kind::HalfSpace;
  g.point = Vec3(0.1, 0.2, 0.3);
  g.normal = Vec3(-1, 0.5, 2).normalized();
  int inside = 0;
  for (int k = 0; k < 10000; ++k) {
    const Vec3 x = random_point(rng, 1.0);
    const bool want = (x - g.point).dot(g.normal) >= 0;
    EXPECT_EQ(g.contains(x), want);
    inside += want;
  }
  EXPECT_GT(inside, 2000);
  EXPECT_LT(inside, 8000);
  EXPECT_TRUE(g.contains(g.point)) << "the plane itself counts as inside";
  EXPECT_TRUE(g.contains(g.point + g.normal));
  EXPECT_FALSE(g.contains(g.point - g.normal));
}

// A closed cube from STL (tests/data/cube.stl, 10 mm in millimetres): points inside the cube
// exactly when every coordinate is in [0, 10] (away from the surface by round-off).
TEST(Region, MeshCubeFromStl) {
  const std::vector<Triangle> tris = read_stl(std::string(DEM_TEST_DATA) + "/cube.stl");
  ClosedMesh cube(std::vector<Tri>(tris.begin(), tris.end()));
  EXPECT_EQ(cube.size(), 12u);
  EXPECT_NEAR(cube.volume(), 1000, 1e-9);
  std::mt19937_64 rng(13);
  int inside = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 x = Vec3::Constant(5) + random_point(rng, 8);
    if ((x.array() - 0).abs().minCoeff() < 1e-9 || (x.array() - 10).abs().minCoeff() < 1e-9) continue;
    const bool want = (x.array() >= 0).all() && (x.array() <= 10).all();
    ASSERT_EQ(cube.contains(x), want) << x.transpose() << ", winding " << cube.winding_number(x);
    inside += want;
  }
  EXPECT_GT(inside, 3000);
  EXPECT_NEAR(cube.winding_number(Vec3(5, 5, 5)), 1, 1e-12) << "outward normals: +1 inside";
  EXPECT_NEAR(cube.winding_number(Vec3(1, 9.5, 0.2)), 1, 1e-12) << "near a corner, still exactly 1";
  EXPECT_NEAR(cube.winding_number(Vec3(5, 5, 10.5)), 0, 1e-12);
  // Turned inside out (every triangle reversed), the same points are inside: -1.
  std::vector<Tri> reversed;
  for (const Triangle& t : tris) reversed.push_back({t[0], t[2], t[1]});
  ClosedMesh inverted(reversed);
  EXPECT_NEAR(inverted.winding_number(Vec3(5, 5, 5)), -1, 1e-12);
  EXPECT_TRUE(inverted.contains(Vec3(5, 5, 5)));
  EXPECT_FALSE(inverted.contains(Vec3(5, 5, 11)));
}

// The twelve triangles of the cube [lo, hi], counter-clockwise seen from outside (inward when `flip`).
std::vector<Tri> cube_triangles(const Vec3& lo, const Vec3& hi, bool flip) {
  std::vector<Vec3> c;
  for (int k = 0; k < 8; ++k) c.emplace_back(k & 1 ? hi[0] : lo[0], k >> 1 & 1 ? hi[1] : lo[1], k >> 2 & 1 ? hi[2] : lo[2]);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Tri> out;
  for (const auto& q : quads) {
    out.push_back({c[q[0]], c[q[1]], c[q[2]]});
    out.push_back({c[q[0]], c[q[2]], c[q[3]]});
  }
  if (flip)
    for (Tri& t : out) std::swap(t[1], t[2]);
  return out;
}

// A hollow cube (an outer surface facing out, an inner one facing in) is not convex: its cavity is
// outside (winding 1 - 1 = 0), its wall inside.
TEST(Region, MeshHollowCube) {
  std::vector<Tri> tris = cube_triangles(Vec3::Zero(), Vec3::Constant(3), false);
  for (const Tri& t : cube_triangles(Vec3::Constant(1), Vec3::Constant(2), true)) tris.push_back(t);
  ClosedMesh hollow(tris);
  EXPECT_NEAR(hollow.volume(), 27 - 1, 1e-12);
  std::mt19937_64 rng(14);
  for (int k = 0; k < 5000; ++k) {
    const Vec3 x = Vec3::Constant(1.5) + random_point(rng, 2);
    const bool in_outer = (x.array() > 0).all() && (x.array() < 3).all();
    const bool in_inner = (x.array() > 1).all() && (x.array() < 2).all();
    const double margin = std::min((x.array() - 0).abs().minCoeff(), std::min((x.array() - 3).abs().minCoeff(),
                                   std::min((x.array() - 1).abs().minCoeff(), (x.array() - 2).abs().minCoeff())));
    if (margin < 1e-9) continue;
    ASSERT_EQ(hollow.contains(x), in_outer && !in_inner) << x.transpose();
  }
}

// any_inside (a sink's test of every particle at every event) answers as contains() over the
// points, for each kind: no point inside, and one inside placed first, in the middle or last,
// below and above the count (16,384) from which it runs on all threads.
TEST(Region, AnyInsideIsContainsOverThePoints) {
  std::vector<Region> kinds(5);
  kinds[0].kind = Region::Kind::Box, kinds[0].min = Vec3(-0.1, -0.1, -0.1), kinds[0].max = Vec3(0.1, 0.1, 0.1);
  kinds[1].kind = Region::Kind::Sphere, kinds[1].radius = 0.1;
  kinds[2].kind = Region::Kind::Cylinder, kinds[2].radius = 0.1, kinds[2].length = 0.2;
  kinds[3].kind = Region::Kind::HalfSpace, kinds[3].point = Vec3(0, 0, -0.5), kinds[3].normal = Vec3(0, 0, -1);
  kinds[4].kind = Region::Kind::Mesh;
  kinds[4].mesh = std::make_shared<ClosedMesh>(cube_triangles(Vec3::Constant(-0.1), Vec3::Constant(0.1), false));
  std::mt19937_64 rng(14);
  for (const long n : {100L, 20000L}) {
    std::vector<Vec3> far(n);  // all outside every region: the shell 0.3 < |x| < 0.4 above z = -0.3
    for (Vec3& x : far) {
      do x = random_point(rng, 0.4);
      while (x.norm() < 0.3 || x.norm() > 0.4 || x.z() < -0.3);
    }
    for (const Region& g : kinds) {
      const Vec3 inside = g.kind == Region::Kind::HalfSpace ? Vec3(0, 0, -0.6) : Vec3(0.01, -0.02, 0.03);
      ASSERT_TRUE(g.contains(inside));
      bool any = false;
      for (const Vec3& x : far) any = any || g.contains(x);
      ASSERT_FALSE(any) << "the far points must all be outside";
      EXPECT_FALSE(g.any_inside(far)) << n << " points, kind " << static_cast<int>(g.kind);
      for (const long at : {0L, n / 2, n - 1}) {
        std::vector<Vec3> one = far;
        one[at] = inside;
        EXPECT_TRUE(g.any_inside(one)) << n << " points, kind " << static_cast<int>(g.kind) << ", the inside one at " << at;
      }
    }
  }
}

// An icosphere of radius R (an icosahedron split 3 times, 1280 triangles, vertices on the sphere):
// a convex polyhedron, so a point is inside exactly when it is behind every face's plane; points
// inside the sphere of the faces' smallest distance are inside, outside the sphere R outside.
TEST(Region, MeshIcosphereAgainstItsPlanesAndTheSphere) {
  const double R = 0.05, t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p = R * p.normalized();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int level = 0; level < 3; ++level) {
    // Split each triangle in four; each edge's midpoint is made once (shared exactly by both sides).
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (const auto it = mid.find(key); it != mid.end()) return it->second;
      v.push_back(R * (v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& q : f) {
      const int ab = middle(q[0], q[1]), bc = middle(q[1], q[2]), ca = middle(q[2], q[0]);
      g.push_back({q[0], ab, ca}), g.push_back({q[1], bc, ab}), g.push_back({q[2], ca, bc}), g.push_back({ab, bc, ca});
    }
    f = g;
  }
  std::vector<Tri> tris;
  double inner = R;  // the smallest distance of a face plane from the centre
  std::vector<std::pair<Vec3, double>> planes;
  for (const auto& q : f) {
    tris.push_back({v[q[0]], v[q[1]], v[q[2]]});
    Vec3 n = (v[q[1]] - v[q[0]]).cross(v[q[2]] - v[q[0]]).normalized();
    if (n.dot(v[q[0]]) < 0) n = -n;  // outward, whichever way the list runs
    planes.emplace_back(n, n.dot(v[q[0]]));
    inner = std::min(inner, std::abs(n.dot(v[q[0]])));
  }
  ASSERT_EQ(tris.size(), 1280u);
  ClosedMesh ball(tris);
  const double sphere = 4.0 / 3 * M_PI * R * R * R;
  EXPECT_LT(ball.volume(), sphere) << "inscribed";
  EXPECT_GT(ball.volume(), 0.97 * sphere);
  std::mt19937_64 rng(15);
  int checked = 0, inside = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 x = random_point(rng, 1.2 * R);
    double worst = -INFINITY;  // the largest signed distance in front of a face plane
    for (const auto& [n, d] : planes) worst = std::max(worst, n.dot(x) - d);
    if (std::abs(worst) < 1e-12) continue;
    const bool want = worst < 0;
    ASSERT_EQ(ball.contains(x), want) << x.transpose();
    if (x.norm() < inner) EXPECT_TRUE(ball.contains(x)) << "inside the faces' inner sphere";
    if (x.norm() > R) EXPECT_FALSE(ball.contains(x)) << "outside the sphere";
    ++checked, inside += want;
  }
  EXPECT_GT(checked, 3900);
  EXPECT_NEAR(double(inside) / checked, 4.0 / 3 * M_PI / (2.4 * 2.4 * 2.4), 0.03) << "volume fraction of the sphere in the cube";
}

TEST(Region, MeshThatIsNotClosedIsRejected) {
  const std::vector<Tri> cube = cube_triangles(Vec3::Zero(), Vec3::Constant(1), false);
  auto message = [](std::vector<Tri> tris) {
    try {
      ClosedMesh m(std::move(tris));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::vector<Tri> open(cube.begin(), cube.end() - 1);
  EXPECT_NE(message(open).find("not closed: 3 edges belong to one triangle only"), std::string::npos) << message(open);
  std::vector<Tri> flipped = cube;
  std::swap(flipped[0][1], flipped[0][2]);
  EXPECT_NE(message(flipped).find("not consistently oriented"), std::string::npos) << message(flipped);
  std::vector<Tri> extra = cube;
  extra.push_back(cube[0]);
  extra.push_back({cube[0][0], cube[0][2], cube[0][1]});
  EXPECT_NE(message(extra).find("three or more triangles"), std::string::npos) << message(extra);
  EXPECT_NE(message({}).find("no triangles"), std::string::npos);
  EXPECT_EQ(message(cube), "");
}

const std::string kScene = R"([[material]]
name = "glass"
density = 2500.0
kn = 5.0e4

[generation]
box_min = [0.0, 0.0, 0.0]
box_max = [0.02, 0.02, 0.05]
count = 100
radius_min = 0.001
radius_max = 0.002
materials = { glass = 1.0 }

[[generation.cut]]
region = { type = "half_space", point = [0, 0, 0.03], normal = [0, 0, 2] }

[[generation.cut]]
region = { type = "mesh", file = "cube.stl", scale = 0.001, translate = [0.005, 0.005, 0] }
inside = false

[[stage]]
name = "drill"
duration = 0.1

[[stage.action]]
type = "remove"
region = { type = "cylinder", centre = [0.01, 0.01, 0], radius = 0.003 }

[[stage.action]]
type = "remove"
region = { type = "cylinder", centre = [0.01, 0.01, 0.01], axis = [1, 0, 0], radius = 0.002, length = 0.01 }
)";

TEST(Region, SceneSyntax) {
  // The mesh file is found beside the scene file.
  const Scene s = parse_scene(kScene, std::string(DEM_TEST_DATA) + "/scene.toml");
  ASSERT_TRUE(s.generation);
  ASSERT_EQ(s.generation->cuts.size(), 2u);
  const Region& h = s.generation->cuts[0].region;
  EXPECT_EQ(h.kind, Region::Kind::HalfSpace);
  EXPECT_TRUE(s.generation->cuts[0].inside);
  EXPECT_EQ(h.normal, Vec3(0, 0, 1)) << "normalised";
  EXPECT_TRUE(h.contains(Vec3(0, 0, 0.03)));
  EXPECT_FALSE(h.contains(Vec3(0, 0, 0.029)));
  const Region& m = s.generation->cuts[1].region;
  EXPECT_EQ(m.kind, Region::Kind::Mesh);
  EXPECT_FALSE(s.generation->cuts[1].inside);
  EXPECT_NEAR(m.mesh->volume(), 1e-6, 1e-15) << "scaled from mm";
  EXPECT_TRUE(m.contains(Vec3(0.01, 0.01, 0.005)));
  EXPECT_FALSE(m.contains(Vec3(0.004, 0.01, 0.005))) << "translated by 5 mm";
  ASSERT_EQ(s.stages[0].actions.size(), 2u);
  ASSERT_TRUE(s.stages[0].actions[0].region && s.stages[0].actions[1].region);
  const Region& c = *s.stages[0].actions[0].region;
  EXPECT_EQ(c.kind, Region::Kind::Cylinder);
  EXPECT_EQ(c.axis, Vec3::UnitZ()) << "axis defaults to +z";
  EXPECT_EQ(c.length, 0) << "no length: infinite";
  EXPECT_TRUE(c.contains(Vec3(0.012, 0.01, 100.0)));
  const Region& f = *s.stages[0].actions[1].region;
  EXPECT_EQ(f.axis, Vec3::UnitX());
  EXPECT_EQ(f.length, 0.01);
  EXPECT_TRUE(f.contains(Vec3(0.015, 0.01, 0.011)));
  EXPECT_FALSE(f.contains(Vec3(0.0151, 0.01, 0.011))) << "beyond half the length";
}

}  // namespace
}  // namespace dem
