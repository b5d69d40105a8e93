// Wall contact geometry (SPEC §3, eq. 2.4-2.5): the contact point is the projection of the centre
// if it falls inside the polygon, else the nearest point of its boundary (edge or vertex); the
// force acts along the line from that point to the centre. Expected points are computed by hand.
#include <gtest/gtest.h>

#include <cmath>

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

// closest_point on a placed element reads the edges' inward normals computed when it was placed:
// they must follow the element as it moves (here a quad turning about a tilted axis) and give the
// polygon's own closest point, bit for bit, inside and outside it. Each point is also checked
// against the vertices: none is nearer than the closest point (tolerance: round-off, 1e-15).
TEST(WallGeometry, PlacedElementsClosestPointsFollowTheirMotion) {
  WallMotion turning;
  turning.centre = Vec3(0.3, 0.2, 0);
  turning.axis = Vec3(1, 1, 1).normalized();
  turning.angular_speed = 2.0;
  const Wall w{"w", 0, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0), Vec3(0, 0.5, 0)}, turning};
  WallGeometry g;
  for (double t : {0.0, 0.4, 1.3}) {
    place_wall(w, t, 1e-3, g);
    for (double a = -0.5; a <= 1.5; a += 0.25)
      for (double b = -0.5; b <= 1.0; b += 0.25)
        for (double c : {-0.3, 0.2}) {
          const Vec3 p = w.motion.place(Vec3(a, b, c), t);
          const Vec3 q = closest_point(g, p);
          EXPECT_EQ(q, closest_point_on_polygon(g.vertices.data(), g.count, g.normal, p)) << "t = " << t << ", p = " << p.transpose();
          for (int v = 0; v < g.count; ++v) EXPECT_LE((q - p).norm(), (g.vertices[v] - p).norm() + 1e-15);
        }
  }
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
// order; they must equal the candidates' own sums in key order (wall_loads(true), which reads the
// candidates for their torques) at every step: while contacts begin and end, the storage re-sorted
// under them. Exact: the same additions in the same order.
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
  for (int step = 0; step < 3000; ++step) {
    sim.advance();
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
  EXPECT_GT(began, 5) << "wall contacts must begin during the run for the test to mean anything";
  EXPECT_GT(ended, 5) << "and end";
}

}  // namespace
}  // namespace dem
