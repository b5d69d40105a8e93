// The container of `compact` and the stage servo (walls/container.hpp): a convex polytope cut plane
// by plane, and the container of a box whose faces have moved in (faces keep their size, so they
// poke through each other) against the exact volume and face areas.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <random>

#include "state/particles.hpp"
#include "walls/container.hpp"
#include "walls/wall.hpp"

namespace dem {
namespace {

constexpr double kRel = 1e-12;  // round-off

TEST(ConvexPolytope, BoxCutByAxisPlanesGivesTheSmallerBox) {
  ConvexPolytope p(Vec3(0, 0, 0), Vec3(1, 2, 3));
  EXPECT_NEAR(p.volume(), 6, 6 * kRel);
  p.clip(HalfSpace::through(Vec3(0.2, 0, 0), Vec3::UnitX()));   // x >= 0.2
  p.clip(HalfSpace::through(Vec3(0.9, 0, 0), -Vec3::UnitX()));  // x <= 0.9
  p.clip(HalfSpace::through(Vec3(0, 0.1, 0), Vec3::UnitY()));   // y >= 0.1
  p.clip(HalfSpace::through(Vec3(0, 0, 2.5), -Vec3::UnitZ()));  // z <= 2.5
  p.clip(HalfSpace::through(Vec3(0, 0, 0), Vec3::UnitZ()));     // the floor's own plane: no change
  const double ex = 0.7, ey = 1.9, ez = 2.5;
  EXPECT_NEAR(p.volume(), ex * ey * ez, ex * ey * ez * kRel);
  EXPECT_EQ(p.faces().size(), 6u);
  const struct {
    Vec3 point, normal;
    double area;
  } faces[] = {{Vec3(0.2, 0, 0), Vec3::UnitX(), ey * ez},  {Vec3(0.9, 0, 0), -Vec3::UnitX(), ey * ez},
               {Vec3(0, 0.1, 0), Vec3::UnitY(), ex * ez},  {Vec3(0, 2, 0), -Vec3::UnitY(), ex * ez},
               {Vec3(0, 0, 0), Vec3::UnitZ(), ex * ey},    {Vec3(0, 0, 2.5), -Vec3::UnitZ(), ex * ey}};
  for (const auto& f : faces) {
    const Polygon face = p.face_in(HalfSpace::through(f.point, f.normal));
    EXPECT_NEAR(polygon_area(face), f.area, f.area * kRel) << f.normal.transpose();
  }
  EXPECT_TRUE(p.face_in(HalfSpace::through(Vec3(0, 0, 1), Vec3::UnitZ())).empty()) << "no face at z = 1";
  p.clip(HalfSpace::through(Vec3(0, 0, 2.6), Vec3::UnitZ()));  // z >= 2.6: nothing left
  EXPECT_TRUE(p.empty());
  EXPECT_EQ(p.volume(), 0);
}

// A unit cube without the corner x + y + z < 1: a tetrahedron of volume 1/6 goes, and the cut is an
// equilateral triangle of side sqrt(2), area sqrt(3)/2; faces stay counter-clockwise seen from outside.
TEST(ConvexPolytope, ObliqueCutOffACorner) {
  ConvexPolytope p(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const HalfSpace h = HalfSpace::through(Vec3(1, 0, 0), Vec3(1, 1, 1).normalized());
  p.clip(h);
  EXPECT_NEAR(p.volume(), 1 - 1.0 / 6, kRel);
  EXPECT_EQ(p.faces().size(), 7u);
  EXPECT_NEAR(polygon_area(p.face_in(h)), std::sqrt(3.0) / 2, kRel);
  for (const Polygon& f : p.faces()) {
    Vec3 n = Vec3::Zero(), c = Vec3::Zero();
    for (std::size_t i = 0; i < f.size(); ++i) n += f[i].cross(f[(i + 1) % f.size()]), c += f[i];
    c /= static_cast<double>(f.size());
    EXPECT_GT(n.dot(c - Vec3(0.6, 0.6, 0.6)), 0) << "outward";
  }
  // A second cut through the same corner region of the opposite corner leaves both cuts.
  p.clip(HalfSpace::through(Vec3(1, 1, 0), -Vec3(1, 1, 1).normalized()));  // x + y + z <= 2
  EXPECT_NEAR(p.volume(), 1 - 2.0 / 6, kRel);
}

TEST(ConvexPolygon, ClipToAWindow) {
  const Polygon square = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)};
  const Polygon window = {Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(3, 3, 0), Vec3(1, 3, 0)};
  EXPECT_NEAR(polygon_area(clip_polygon_to(square, window)), 1, kRel);
  const Polygon tri = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};  // x + y <= 4: half the window
  EXPECT_NEAR(polygon_area(clip_polygon_to(window, tri)), 2, kRel);
  EXPECT_TRUE(clip_polygon_to(square, {Vec3(5, 5, 0), Vec3(6, 5, 0), Vec3(6, 6, 0)}).empty());
  // A polygon touching a plane, or lying in it, comes back whole.
  EXPECT_EQ(clip_polygon(square, HalfSpace::through(Vec3(0, 0, 0), Vec3::UnitX()), 1e-12), square);
  EXPECT_EQ(clip_polygon(square, HalfSpace::through(Vec3(0, 0, 0), Vec3::UnitZ()), 1e-12), square);
}

// A box [lo, hi] as six face walls (box.xmin, box.xmax, ... as the scene parser makes them).
std::vector<Wall> box_walls(const Vec3& lo, const Vec3& hi) {
  std::vector<Wall> walls;
  const char* names[3][2] = {{"box.xmin", "box.xmax"}, {"box.ymin", "box.ymax"}, {"box.zmin", "box.zmax"}};
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) walls.push_back(Wall{names[a][side], 0, box_face(lo, hi, a, side == 1), {}});
  return walls;
}

// Particles spread inside [lo, hi] (their centres only matter, and the top sphere under gravity).
Particles spheres_in(const Vec3& lo, const Vec3& hi, double a, std::mt19937_64& rng, int count = 50) {
  Particles p;
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < count; ++k) {
    Vec3 x;
    for (int c = 0; c < 3; ++c) x[c] = lo[c] + a + (hi[c] - lo[c] - 2 * a) * u(rng);
    p.add(k, x, a, 1000, 0);
  }
  return p;
}

// Every subset of the six faces moved inward by random distances (without gravity): the volume is
// the product of the edges between the faces' planes, and each face's area the product of the two
// edges across it; with nothing moving, the original box.
TEST(Container, BoxWithAnySubsetOfFacesMovedIn) {
  const Vec3 lo(0, 0, 0), hi(0.03, 0.02, 0.04);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> shift(0.001, 0.005);
  for (int subset = 0; subset < 64; ++subset) {
    std::vector<Wall> walls = box_walls(lo, hi);
    Vec3 now_lo = lo, now_hi = hi;
    for (int f = 0; f < 6; ++f) {
      if (!(subset >> f & 1)) continue;
      const int axis = f / 2;
      const double s = shift(rng);
      (f % 2 ? now_hi : now_lo)[axis] += f % 2 ? -s : s;
      walls[f].motion.velocity[axis] = (f % 2 ? -s : s) / 0.5;  // reaches the shift at t = 0.5 s
    }
    const Particles p = spheres_in(now_lo, now_hi, 5e-4, rng);
    Container c(walls, 0.5, p, Vec3::Zero());
    const Vec3 e = now_hi - now_lo;
    EXPECT_NEAR(c.volume(), e.prod(), e.prod() * kRel) << "subset " << subset;
    for (int f = 0; f < 6; ++f) {
      const int a = f / 2;
      const double want = e[(a + 1) % 3] * e[(a + 2) % 3];
      EXPECT_NEAR(c.wall_area(f), want, want * kRel) << "subset " << subset << ", " << walls[f].name;
    }
    if (subset == 0) {
      EXPECT_NEAR(c.volume(), 0.03 * 0.02 * 0.04, 1e-20) << "nothing moved: the box itself";
      EXPECT_NEAR(c.wall_area(5), 0.03 * 0.02, 1e-20) << "nothing moved: the lid's quad";
    }
  }
}

// The area a wall gets is the polytope's face in its plane within its polygon, computed the long
// way here: the box cut by all six planes, the face found, clipped to the wall's quad.
TEST(Container, WallAreaIsThePolytopeFaceWithinTheWall) {
  const Vec3 lo(0, 0, 0), hi(0.03, 0.02, 0.04);
  std::vector<Wall> walls = box_walls(lo, hi);
  walls[0].motion.velocity = Vec3(0.004, 0, 0);   // xmin in by 4 mm
  walls[3].motion.velocity = Vec3(0, -0.003, 0);  // ymax in by 3 mm
  walls[5].motion.velocity = Vec3(0, 0, -0.01);   // the lid down by 10 mm
  std::mt19937_64 rng(2);
  const Particles p = spheres_in(Vec3(0.004, 0, 0), Vec3(0.03, 0.017, 0.03), 5e-4, rng);
  Container c(walls, 1.0, p, Vec3::Zero());
  ConvexPolytope shape(lo, hi);
  std::vector<HalfSpace> planes;
  for (const Wall& w : walls) {
    const Polygon v = w.vertices_at(1.0);
    Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    if (n.dot(Vec3(0.015, 0.01, 0.02) - v[0]) < 0) n = -n;
    planes.push_back(HalfSpace::through(v[0], n));
    shape.clip(planes.back());
  }
  EXPECT_NEAR(c.volume(), shape.volume(), shape.volume() * kRel);
  EXPECT_NEAR(shape.volume(), 0.026 * 0.017 * 0.03, 1e-18);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const double want = polygon_area(clip_polygon_to(shape.face_in(planes[k]), walls[k].vertices_at(1.0)));
    EXPECT_GT(want, 0);
    EXPECT_NEAR(c.wall_area(k), want, want * kRel) << walls[k].name;
  }
  EXPECT_NEAR(c.wall_area(5), 0.026 * 0.017, 1e-18) << "the lid: the cross-section between the side walls";
}

// Under gravity an open box (no lid) is cut at the top of the highest sphere, as is a lid far above
// the bed; the side walls count their area below that top; a wall the spheres lie on both sides of
// (a baffle standing in the bed) bounds nothing.
TEST(Container, CutAtTheTopOfTheSpheresAndWallsInsideTheBedIgnored) {
  const Vec3 lo(0, 0, 0), hi(0.02, 0.02, 0.1);
  std::vector<Wall> walls = box_walls(lo, hi);
  walls.push_back(Wall{"baffle", 0, {Vec3(0.01, 0.005, 0.0), Vec3(0.01, 0.015, 0.0), Vec3(0.01, 0.015, 0.02), Vec3(0.01, 0.005, 0.02)}, {}});
  std::mt19937_64 rng(3);
  Particles p = spheres_in(lo, Vec3(0.02, 0.02, 0.03), 1e-3, rng);
  p.add(99, Vec3(0.005, 0.005, 0.035), 1e-3, 1000, 0);  // the top sphere, top at z = 0.036
  const double top = 0.036;
  for (bool lid : {true, false}) {
    std::vector<Wall> w = walls;
    if (!lid) w.erase(w.begin() + 5);
    Container c(w, 0, p, Vec3(0, 0, -9.81));
    EXPECT_NEAR(c.volume(), 0.02 * 0.02 * top, 1e-18) << (lid ? "lid far above" : "open box");
    EXPECT_NEAR(c.wall_area(0), 0.02 * top, 1e-18) << "a side wall, up to the top of the bed";
    EXPECT_NEAR(c.wall_area(4), 0.02 * 0.02, 1e-18) << "the floor";
    if (lid) EXPECT_NEAR(c.wall_area(5), 0.02 * 0.02, 1e-18) << "a lid above the bed keeps its area between the walls";
  }
}

// A plane that cuts the centres' bounding box but has every centre on its inner side still bounds
// them (the corners' shortcut does not answer; the pass over the centres does): an oblique wall
// x + y = 0.025 across the corner of a 0.02 m box, three spheres whose box reaches (0.015, 0.015)
// beyond it but whose centres all lie within; the side wall x = 0.02 keeps y <= 0.005 of its
// height. A fourth sphere beyond the plane makes it bound nothing: the full face again.
TEST(Container, PlaneAcrossTheCentresBoxButBehindEveryCentre) {
  const Vec3 lo(0, 0, 0), hi(0.02, 0.02, 0.01);
  std::vector<Wall> walls = box_walls(lo, hi);
  walls.push_back(Wall{"corner", 0, {Vec3(0.005, 0.02, 0), Vec3(0.02, 0.005, 0), Vec3(0.02, 0.005, 0.01), Vec3(0.005, 0.02, 0.01)}, {}});
  Particles p;
  p.add(0, Vec3(0.005, 0.005, 0.005), 1e-3, 1000, 0);
  p.add(1, Vec3(0.015, 0.005, 0.005), 1e-3, 1000, 0);
  p.add(2, Vec3(0.005, 0.015, 0.005), 1e-3, 1000, 0);
  Container c(walls, 0, p, Vec3::Zero());
  EXPECT_NEAR(c.wall_area(1), 0.005 * 0.01, 1e-17) << "box.xmax, cut by the corner wall";
  p.add(3, Vec3(0.0145, 0.0145, 0.005), 1e-3, 1000, 0);  // x + y = 0.029: beyond the corner wall
  Container beyond(walls, 0, p, Vec3::Zero());
  EXPECT_NEAR(beyond.wall_area(1), 0.02 * 0.01, 1e-17) << "box.xmax: the corner wall has a centre beyond it";
}

// A sample as large as users bring (10,000 centres: the container's pass over them runs in chunks
// of 4,096, in parallel): the same answers as above when what decides them lies in the last chunk
// (the top sphere; the one centre beyond an oblique wall), and the same bits on one thread and two.
TEST(Container, TenThousandCentresGiveTheSameAnswersOnAnyThreadCount) {
  const int threads_before = omp_get_max_threads();
  const Vec3 lo(0, 0, 0), hi(0.02, 0.02, 0.1);
  std::vector<Wall> walls = box_walls(lo, hi);
  walls.push_back(Wall{"corner", 0, {Vec3(0.005, 0.02, 0), Vec3(0.02, 0.005, 0), Vec3(0.02, 0.005, 0.1), Vec3(0.005, 0.02, 0.1)}, {}});
  std::mt19937_64 rng(7);
  Particles p = spheres_in(lo, Vec3(0.0125, 0.0125, 0.03), 1e-3, rng, 10000);  // every centre has x + y < 0.0235
  p.add(10000, Vec3(0.005, 0.005, 0.035), 1e-3, 1000, 0);                    // the top sphere, top at z = 0.036
  ASSERT_GT(p.size(), 2u * 4096) << "the centres must fill more than two chunks";
  const double top = 0.036;
  double volume[2], area[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Container c(walls, 0, p, Vec3(0, 0, -9.81));
    volume[threads - 1] = c.volume(), area[threads - 1] = c.wall_area(1);
    // The box cut at the top and by the corner wall x + y <= 0.025: 0.02^2 less the corner's
    // triangle of legs 0.015.
    EXPECT_NEAR(c.volume(), (0.02 * 0.02 - 0.5 * 0.015 * 0.015) * top, 1e-18) << threads << " threads";
    EXPECT_NEAR(c.wall_area(1), 0.005 * top, 1e-18) << "box.xmax, cut by the corner wall and the top";
  }
  EXPECT_EQ(volume[0], volume[1]);
  EXPECT_EQ(area[0], area[1]);
  p.add(10001, Vec3(0.0145, 0.0145, 0.005), 1e-3, 1000, 0);  // beyond the corner wall, in the last chunk
  omp_set_num_threads(2);
  Container beyond(walls, 0, p, Vec3(0, 0, -9.81));
  EXPECT_NEAR(beyond.wall_area(1), 0.02 * top, 1e-18) << "box.xmax: the corner wall has a centre beyond it";
  omp_set_num_threads(threads_before);
}

}  // namespace
}  // namespace dem
