// Wall contact geometry (SPEC §3, eq. 2.4-2.5): the contact point is the projection of the centre
// if it falls inside the polygon, else the nearest point of its boundary (edge or vertex); the
// force acts along the line from that point to the centre. Expected points are computed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <omp.h>

#include "sim/simulation.hpp"
#include "walls/wall.hpp"

namespace dem {
namespace {

const std::vector<Vec3> kTriangle = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};

Vec3 closest(const Vec3& p) { return closest_point_on_polygon(kTriangle.data(), 3, Vec3::UnitZ(), p); }

TEST(WallGeometry, FaceEdgeAndVertexRegions) {
  EXPECT_EQ(closest(Vec3(0.2, 0.3, 0.5)), Vec3(0.2, 0.3, 0)) << "face: projection";
  EXPECT_EQ(closest(Vec3(0.5, -0.4, 0.1)), Vec3(0.5, 0, 0)) << "edge y = 0";
  EXPECT_TRUE(closest(Vec3(0.8, 0.8, -0.2)).isApprox(Vec3(0.5, 0.5, 0), 1e-15)) << "hypotenuse";
  EXPECT_EQ(closest(Vec3(-0.3, -0.2, 0.1)), Vec3(0, 0, 0)) << "vertex at the origin";
  EXPECT_EQ(closest(Vec3(1.5, -0.1, 0)), Vec3(1, 0, 0)) << "vertex (1, 0, 0)";
}

// closest_point on a placed element reads the normal and the edges' inward normals worked out where
// its motion started and turned with it (docs/physics.md, after P23): they must follow the element
// as it moves (here a quad turning about a tilted axis) and match those worked out afresh from the
// moved vertices, and give the polygon's own closest point, inside and outside it. Tolerances:
// round-off, 1e-15 for unit directions; 1e-14 for points a unit from the origin, where a point on
// an edge may fall on either side of it by one rounding (then both closest points are the same
// point to round-off). Each point is also checked against the vertices: none is nearer than the
// closest point (1e-15).
TEST(WallGeometry, PlacedElementsClosestPointsFollowTheirMotion) {
  WallMotion turning;
  turning.centre = Vec3(0.3, 0.2, 0);
  turning.axis = Vec3(1, 1, 1).normalized();
  turning.angular_speed = 2.0;
  const Wall w{"w", 0, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0), Vec3(0, 0.5, 0)}, turning};
  WallGeometry g;
  for (double t : {0.0, 0.4, 1.3}) {
    place_wall(w, t, 1e-3, g);
    const Vec3 fresh_normal = (g.vertices[1] - g.vertices[0]).cross(g.vertices[2] - g.vertices[0]).normalized();
    EXPECT_LE((g.normal - fresh_normal).norm(), 1e-15) << "t = " << t;
    std::array<Vec3, 4> fresh_inward;
    inward_normals(g.vertices.data(), g.count, fresh_normal, fresh_inward.data());
    for (int k = 0; k < g.count; ++k) EXPECT_LE((g.inward[k] - fresh_inward[k]).norm(), 1e-15 * fresh_inward[k].norm()) << "t = " << t;
    for (double a = -0.5; a <= 1.5; a += 0.25)
      for (double b = -0.5; b <= 1.0; b += 0.25)
        for (double c : {-0.3, 0.2}) {
          const Vec3 p = w.motion.place(Vec3(a, b, c), t);
          const Vec3 q = closest_point(g, p);
          EXPECT_LE((q - closest_point_on_polygon(g.vertices.data(), g.count, fresh_normal, p)).norm(), 1e-14)
              << "t = " << t << ", p = " << p.transpose();
          for (int v = 0; v < g.count; ++v) EXPECT_LE((q - p).norm(), (g.vertices[v] - p).norm() + 1e-15);
        }
  }
}

// The frame a placed element keeps (its base and the base's normals) must follow a new base: a
// stage's motion starting where the last left the element (Wall::start_motion), a fixed element
// after a turning one, and another element placed into the same geometry. Each placement must equal
// a first placement into fresh geometry, bit for bit (the same arithmetic from the same base).
TEST(WallGeometry, PlacedElementsFollowANewBase) {
  WallMotion turning;
  turning.centre = Vec3(0.3, 0.2, 0);
  turning.axis = Vec3(0, 0, 1);
  turning.angular_speed = 3.0;
  Wall w{"w", 0, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0.1), Vec3(0, 0.5, 0.1)}, turning};
  auto same_as_fresh = [](const Wall& wall, double t, const WallGeometry& g) {
    WallGeometry fresh;
    place_wall(wall, t, 1e-3, fresh);
    EXPECT_EQ(g.count, fresh.count);
    for (int v = 0; v < fresh.count; ++v) EXPECT_EQ(g.vertices[v], fresh.vertices[v]) << "t = " << t << ", vertex " << v;
    for (int k = 0; k < fresh.count; ++k) EXPECT_EQ(g.inward[k], fresh.inward[k]) << "t = " << t << ", edge " << k;
    EXPECT_EQ(g.normal, fresh.normal);
    EXPECT_EQ(g.velocity, fresh.velocity);
    EXPECT_EQ(g.spin, fresh.spin);
  };
  WallGeometry g;
  place_wall(w, 0.2, 1e-3, g);
  same_as_fresh(w, 0.2, g);
  WallMotion tilted = turning;
  tilted.axis = Vec3(1, 0, 1).normalized();
  w.start_motion(tilted, 0.5);  // a new stage: the base is where the first motion left it
  place_wall(w, 0.7, 1e-3, g);
  same_as_fresh(w, 0.7, g);
  w.start_motion(WallMotion{}, 0.9);  // then held still
  place_wall(w, 1.0, 1e-3, g);
  same_as_fresh(w, 1.0, g);
  EXPECT_EQ(g.velocity, Vec3::Zero());
  const Wall other{"other", 0, {Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(2, 1, 0)}, turning};
  place_wall(other, 1.0, 1e-3, g);  // a triangle into the quad's geometry
  same_as_fresh(other, 1.0, g);
}

// A step places the walls' elements on one thread below 1,000 and on every thread above, each
// thread keeping one rotation for the elements after the first (RotationCache). Either way every
// element must be placed exactly as on its own (place_wall into fresh geometry, one rotation
// each): with 400 and with 1,200 elements, on one and two threads, two meshes interleaved that
// turn at the same rate about different axes (the same angle: the cache must tell them apart by
// the axis).
TEST(WallGeometry, ElementsPlacedTogetherEqualEachPlacedAlone) {
  for (int elements : {400, 1200}) {
    for (int threads : {1, 2}) {
      Material m;
      m.name = "m";
      m.kn = 1e4, m.kt = 2e3;
      Simulation sim;
      sim.materials = MaterialTable({m}, {});
      sim.params.parallel_min_particles = 0;
      WallMotion about_z, about_x;
      about_z.axis = Vec3::UnitZ(), about_z.angular_speed = 5.0;
      about_x.axis = Vec3::UnitX(), about_x.centre = Vec3(0, 0, 1), about_x.angular_speed = 5.0;
      for (int e = 0; e < elements; ++e) {
        const double a0 = 0.01 * e, a1 = a0 + 0.01, z = 0.001 * e;
        sim.walls.push_back(Wall{"w", 0,
                                 {Vec3(0.1 * std::cos(a0), 0.1 * std::sin(a0), z), Vec3(0.3 * std::cos(a0), 0.3 * std::sin(a0), z + 0.01),
                                  Vec3(0.3 * std::cos(a1), 0.3 * std::sin(a1), z + 0.011), Vec3(0.1 * std::cos(a1), 0.1 * std::sin(a1), z + 0.001)},
                                 e % 2 ? about_x : about_z});
      }
      sim.particles.add(0, Vec3(5, 5, 5), 0.01, 2500, 0);  // far from every element
      sim.dt = 1e-4;
      const int before = omp_get_max_threads();
      omp_set_num_threads(threads);
      double t = 0;  // the last step places them at its start
      for (int step = 0; step < 3; ++step) t = sim.time, sim.advance();
      omp_set_num_threads(before);
      ASSERT_EQ(sim.wall_geometry().size(), static_cast<std::size_t>(elements));
      for (int e = 0; e < elements; ++e) {
        WallGeometry alone;
        place_wall(sim.walls[e], t, sim.dt, alone);
        const WallGeometry& g = sim.wall_geometry()[e];
        for (int v = 0; v < 4; ++v) ASSERT_EQ(g.vertices[v], alone.vertices[v]) << elements << " elements, " << threads << " threads, element " << e;
        for (int k = 0; k < 4; ++k) ASSERT_EQ(g.inward[k], alone.inward[k]) << elements << " elements, element " << e;
        ASSERT_EQ(g.normal, alone.normal) << elements << " elements, element " << e;
      }
    }
  }
}

// The boundary search looks only at the edges whose outer side holds the projection
// (docs/physics.md P21). Against the nearest point of every edge, searched here by sampling each
// edge finely and refining (independent of the library's segment projection), for random convex
// triangles and quads (sharp and blunt corners) and points on both sides, inside and outside:
// the distances agree within 1e-12 of the polygon's size (round-off of the two computations).
TEST(WallGeometry, BoundarySearchFindsTheNearestEdgePoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int outside = 0;
  for (int poly = 0; poly < 200; ++poly) {
    const int n = poly % 2 ? 4 : 3;
    // Convex: points on an ellipse at increasing angles (counter-clockwise about +z).
    std::vector<double> angle(n);
    for (double& a : angle) a = std::numbers::pi * (u(rng) + 1);
    std::sort(angle.begin(), angle.end());
    const double rx = 0.5 + std::abs(u(rng)), ry = 0.5 + std::abs(u(rng));
    std::vector<Vec3> v;
    for (double a : angle) v.emplace_back(rx * std::cos(a), ry * std::sin(a), 0);
    if (!polygon_problem(v).empty()) continue;
    for (int k = 0; k < 20; ++k) {
      const Vec3 p(3 * u(rng), 3 * u(rng), u(rng));
      const Vec3 c = closest_point_on_polygon(v.data(), n, Vec3::UnitZ(), p);
      // Every edge sampled at 2,001 points, then the best sample refined by ternary search.
      double best = std::numeric_limits<double>::infinity();
      for (int e = 0; e < n; ++e) {
        const Vec3 a = v[e], b = v[(e + 1) % n];
        const auto dist = [&](double s) { return (a + s * (b - a) - p).norm(); };
        int best_i = 0;
        for (int i = 1; i <= 2000; ++i)
          if (dist(i / 2000.0) < dist(best_i / 2000.0)) best_i = i;
        double lo = std::max(0.0, (best_i - 1) / 2000.0), hi = std::min(1.0, (best_i + 1) / 2000.0);
        for (int it = 0; it < 200; ++it) {  // the distance along a segment is convex
          const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
          if (dist(m1) < dist(m2)) hi = m2;
          else lo = m1;
        }
        best = std::min(best, dist(0.5 * (lo + hi)));
      }
      const Vec3 q(p.x(), p.y(), 0);  // the projection
      bool inside = true;
      for (int e = 0; e < n; ++e) inside = inside && (v[(e + 1) % n] - v[e]).cross(q - v[e]).z() >= 0;
      if (inside) {
        EXPECT_EQ(c, q);
      } else {
        ++outside;
        EXPECT_NEAR((c - p).norm(), best, 1e-12) << "polygon " << poly << ", point " << p.transpose();
      }
    }
  }
  EXPECT_GT(outside, 2000) << "most points outside, so the edge search is what is tested";
}

TEST(WallGeometry, PolygonChecks) {
  EXPECT_EQ(polygon_problem(kTriangle), "");
  EXPECT_NE(polygon_problem({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}), "") << "bow-tie quad";
  EXPECT_NE(polygon_problem({Vec3(0, 0, 0), Vec3(1, 0, 0)}), "") << "two vertices";
}

// A sphere resting against an edge (or a vertex) of a triangle feels the linear spring force
// k_n u along the line from the contact point to its centre, where u = a - distance.
TEST(WallContact, EdgeAndVertexForceAlongTheLineToTheCentre) {
  Material m;
  m.name = "m";
  m.kn = m.kt = 1e4;
  m.restitution = m.restitution_t = 1.0;  // no damping: the force is the spring alone
  for (const Vec3& centre : {Vec3(0.5, -0.0008, 0.0006), Vec3(-0.0006, -0.0006, 0.0005)}) {
    Simulation sim;
    sim.materials = MaterialTable({m}, {});
    sim.params.gravity = Vec3::Zero();
    sim.walls.push_back(Wall{"tri", 0, kTriangle, {}});
    const double a = 0.0011;
    sim.particles.add(0, centre, a, 2500, 0);
    sim.dt = 1e-9;
    sim.advance();
    ASSERT_EQ(sim.wall_contacts().size(), 1u);
    const Vec3 cp = closest(centre);
    const Vec3 d = centre - cp;
    const Vec3 want = 1e4 * (a - d.norm()) * d.normalized();
    EXPECT_TRUE(sim.wall_contacts().force(0).isApprox(want, 1e-12)) << sim.wall_contacts().force(0).transpose() << " vs " << want.transpose();
  }
}

// The walls' loads (a servo reads them every step) come from copies the force loop keeps in key
// order while they are asked for every step; they must equal the candidates' own sums in key order
// (wall_loads(true), which reads the candidates for their torques) at every step: while contacts
// begin and end, the storage re-sorted under them, and after stretches of steps in which nobody
// asked (the loop then writes no copies, and must not read stale ones after). Exact: the same
// additions in the same order.
TEST(WallLoads, TheForceLoopsCopiesEqualTheCandidatesAtEveryStep) {
  Material m;
  m.name = "m";
  m.kn = 1e4, m.kt = 2e3;
  m.restitution = m.restitution_t = 0.9;  // bouncing: wall contacts end and begin again
  Simulation sim;
  sim.materials = MaterialTable({m}, {});
  const Vec3 hi(0.012, 0.012, 0.012);
  for (int axis = 0; axis < 3; ++axis)
    for (bool side : {false, true}) sim.walls.push_back(Wall{"w", 0, box_face(Vec3::Zero(), hi, axis, side), {}});
  Index id = 0;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z) {
        sim.particles.add(id, Vec3(0.002 + 0.004 * x, 0.002 + 0.004 * y, 0.002 + 0.004 * z), 0.001, 2500, 0);
        sim.particles.v.back() = Vec3(0.3 * (x - 1) + 0.05 * z, 0.2 * (y - 1) - 0.05 * x, -0.4 + 0.1 * y);
        ++id;
      }
  sim.params.sort_every = 50, sim.params.sort_min_particles = 0;  // slots apart from key order
  sim.dt = 1e-5;
  long began = 0, ended = 0;
  int before = 0;
  long from_copies = 0;
  for (int step = 0; step < 3000; ++step) {
    sim.advance();
    if (step % 20 >= 17) continue;  // nobody asks for three steps (a contact may end in them)
    from_copies += sim.wall_loads_from_copies();
    EXPECT_EQ(sim.wall_loads_from_copies(), step % 20 != 0) << "step " << step << ": copies kept from the second step asked on";
    const std::vector<WallLoad> copied = sim.wall_loads(false), direct = sim.wall_loads(true);
    ASSERT_EQ(copied.size(), direct.size());
    int now = 0;
    for (std::size_t w = 0; w < copied.size(); ++w) {
      ASSERT_EQ(copied[w].contacts, direct[w].contacts) << "step " << step << ", wall " << w;
      ASSERT_TRUE(copied[w].force.x() == direct[w].force.x() && copied[w].force.y() == direct[w].force.y() &&
                  copied[w].force.z() == direct[w].force.z())
          << "step " << step << ", wall " << w << ": " << copied[w].force.transpose() << " vs " << direct[w].force.transpose();
      now += copied[w].contacts;
    }
    began += now > before, ended += now < before;
    before = now;
  }
  EXPECT_GT(from_copies, 2000);
  EXPECT_GT(began, 5) << "wall contacts must begin during the run for the test to mean anything";
  EXPECT_GT(ended, 5) << "and end";
}

}  // namespace
}  // namespace dem
