// Contact with mesh walls (SPEC §3): where elements meet, a touch seen by several elements counts
// once on flat and convex surfaces and once per face in a concave corner; a sphere moving across
// element edges feels what it feels on a single plane. The expected forces come from geometry
// computed here by brute force (the closest point of the whole surface), not from the force loop.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "search/neighbour_list.hpp"
#include "forces/force_loop.hpp"
#include "sim/simulation.hpp"
#include "walls/wall.hpp"

namespace dem {
namespace {

Material elastic(double kn) {
  Material m;
  m.name = "m";
  m.kn = m.kt = kn;
  m.restitution = m.restitution_t = 1.0;  // no dashpots: a first step from rest feels the spring alone
  m.friction_angle = 30;
  return m;
}

// A flat square [0, L]^2 at z = 0 split into n x n cells, each cut into two triangles along a
// diagonal whose direction alternates, so edges and vertices of 4, 6 and 8 elements occur.
std::vector<Wall> split_square(double L, int n, const std::string& name = "floor") {
  std::vector<Wall> walls;
  auto p = [&](int i, int j) { return Vec3(L * i / n, L * j / n, 0); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::string base = name + "." + std::to_string(walls.size());
      if ((i + j) % 2 == 0) {
        walls.push_back(Wall{base, 0, {p(i, j), p(i + 1, j), p(i + 1, j + 1)}, {}});
        walls.push_back(Wall{base + "b", 0, {p(i, j), p(i + 1, j + 1), p(i, j + 1)}, {}});
      } else {
        walls.push_back(Wall{base, 0, {p(i, j), p(i + 1, j), p(i, j + 1)}, {}});
        walls.push_back(Wall{base + "b", 0, {p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)}, {}});
      }
    }
  return walls;
}

// Force on a sphere at rest at `centre` after one step (zero gravity): m dv/dt.
Vec3 force_at(const std::vector<Wall>& walls, const Vec3& centre, double a, double kn) {
  Simulation sim;
  sim.materials = MaterialTable({elastic(kn)}, {});
  sim.params.gravity = Vec3::Zero();
  sim.params.max_overlap = 2;  // deep overlaps are part of the sample
  sim.walls = walls;
  sim.particles.add(0, centre, a, 2500, 0);
  sim.dt = 1e-9;
  sim.advance();
  return sim.particles.v[0] * (sim.particles.mass[0] / sim.dt);
}

// The closest point of the whole surface (all elements) to p: brute force.
Vec3 surface_closest(const std::vector<Wall>& walls, const Vec3& p) {
  Vec3 best = Vec3::Constant(1e300);
  for (const Wall& w : walls) {
    const Vec3 n = (w.base[1] - w.base[0]).cross(w.base[2] - w.base[0]).normalized();
    const Vec3 c = closest_point_on_polygon(w.base.data(), static_cast<int>(w.base.size()), n, p);
    if ((c - p).squaredNorm() < (best - p).squaredNorm()) best = c;
  }
  return best;
}

// On a flat surface split into triangles, and over the convex edges and corners of a block made
// of several elements, the force equals k_n (a - d) along the line from the surface's closest
// point: one contact, never one per element. Tolerance 1e-9 relative: the contact point is
// computed on different elements, which differ by round-off only.
// A wall candidate farther from its element's plane than the radius does not touch; its direction
// (closest point - centre) is still computed where the force loop reads it: a contact of the last
// step (lost now; a new contact may take over its spring) and a bond (held in tension).
TEST(MeshContact, DirectionsOfLostContactsAndBondsAreKept) {
  const double a = 1e-3;
  Particles p;
  p.add(0, Vec3(0.9 * a, 0.5, 1.5 * a), a, 2500, 0);  // 1.5 a above the floor, 0.9 a from the side
  const std::vector<Vec3> floor = box_face(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, false);
  const std::vector<Vec3> side = box_face(Vec3(0, 0, 0), Vec3(1, 1, 1), 0, false);
  std::vector<WallGeometry> g(4);
  for (int w = 0; w < 4; ++w) place_wall(Wall{"w", 0, w % 2 ? side : floor, {}}, 0, 1e-5, g[w]);
  ContactList wc;
  wc.resize(4);
  for (int k = 0; k < 4; ++k) wc.slot_i[k] = 0, wc.slot_j[k] = k, wc.key_i[k] = 0, wc.key_j[k] = k;
  wc.active = {1, 0, 0, 0};  // the floor was a contact at the last step
  wc.bonded = {0, 0, 1, 0};  // the second floor holds a bond
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec3> to_wall(4, Vec3::Constant(nan));
  std::vector<std::uint8_t> touching(4), take(4);
  std::vector<int> order(4);
  counted_wall_touches(p, g, wc, 0, 4, to_wall.data(), touching.data(), take.data(), order.data());
  EXPECT_EQ(touching, (std::vector<std::uint8_t>{0, 1, 0, 1}));
  EXPECT_NEAR((to_wall[0] - Vec3(0, 0, -1.5 * a)).norm(), 0, 1e-15) << "the lost contact's direction";
  EXPECT_NEAR((to_wall[2] - Vec3(0, 0, -1.5 * a)).norm(), 0, 1e-15) << "the bond's direction";
  EXPECT_NEAR((to_wall[1] - Vec3(-0.9 * a, 0, 0)).norm(), 0, 1e-15) << "the touch's direction";
}

TEST(MeshContact, FlatAndConvexSurfacesCountOneTouch) {
  const double a = 0.01, kn = 1e5;
  const std::vector<Wall> flat = split_square(0.1, 4);
  // A block [0, 0.05]^2 x [-0.05, 0]: top split into triangles, sides as quads (convex edges).
  std::vector<Wall> block = split_square(0.05, 2, "top");
  for (const auto& [axis, side] : {std::pair{0, false}, {0, true}, {1, false}, {1, true}})
    block.push_back(Wall{"side" + std::to_string(block.size()), 0, box_face(Vec3(0, 0, -0.05), Vec3(0.05, 0.05, 0), axis, side), {}});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int tested = 0;
  for (const std::vector<Wall>* walls : std::vector<const std::vector<Wall>*>{&flat, &block}) {
    for (int s = 0; s < 400; ++s) {
      // Centres within reach of the surface: over the interior, edges and vertices, and (block)
      // beyond its convex edges and corners.
      const double lo = walls == &flat ? 0.0 : -0.012, hi = walls == &flat ? 0.1 : 0.062;
      const Vec3 centre(lo + (hi - lo) * u(rng), lo + (hi - lo) * u(rng), walls == &flat ? 0.0095 + 4e-4 * u(rng) : -0.012 + 0.0215 * u(rng));
      const Vec3 c = surface_closest(*walls, centre);
      const double d = (centre - c).norm();
      if (d >= a || (walls == &block && centre.z() < 0 && centre.x() > 0 && centre.x() < 0.05 && centre.y() > 0 && centre.y() < 0.05))
        continue;  // not touching, or inside the block
      const Vec3 want = kn * (a - d) * (centre - c).normalized();
      const Vec3 got = force_at(*walls, centre, a, kn);
      ASSERT_LT((got - want).norm(), 1e-9 * want.norm() + 1e-15) << "centre " << centre.transpose() << ": " << got.transpose()
                                                                 << " vs " << want.transpose();
      ++tested;
    }
  }
  EXPECT_GT(tested, 300);
}

// In a concave corner (the floor and a side of a box) both faces push: the force is the sum of the
// two face forces, each k_n (a - d) along its own normal.
TEST(MeshContact, ConcaveCornerCountsBothFaces) {
  const double a = 0.01, kn = 1e5;
  std::vector<Wall> walls = split_square(0.1, 4);
  walls.push_back(Wall{"side", 0, box_face(Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1), 0, false), {}});  // x = 0
  const Vec3 centre(0.0097, 0.033, 0.0094);
  const Vec3 want = kn * (a - centre.z()) * Vec3::UnitZ() + kn * (a - centre.x()) * Vec3::UnitX();
  const Vec3 got = force_at(walls, centre, a, kn);
  EXPECT_LT((got - want).norm(), 1e-9 * want.norm()) << got.transpose() << " vs " << want.transpose();
}

// Bonding to a mesh (stage action bond with walls = true) bonds each touch once: a sphere resting
// on a vertex where 8 triangles meet touches all 8, but the force loop counts one contact, so one
// bond; in the concave corner both faces are contacts and both are bonded.
TEST(MeshContact, BondsToAMeshCountEachTouchOnce) {
  const double a = 0.01;
  for (const bool corner : {false, true}) {
    Simulation sim;
    Material m = elastic(1e5);
    m.law = NormalLaw::Liu;
    m.tensile_strength = 1.0;
    sim.materials = MaterialTable({m}, {});
    sim.walls = split_square(0.1, 4);  // (0.05, 0.05) is a vertex of 8 triangles
    Vec3 centre(0.05, 0.05, a - 1e-6);
    if (corner) {
      sim.walls.push_back(Wall{"side", 0, box_face(Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1), 0, false), {}});
      centre = Vec3(a - 1e-6, 0.05, a - 1e-6);  // (0, 0.05) is a vertex of 4 floor triangles
    }
    sim.particles.add(0, centre, a, 2500, 0);
    sim.dt = 1e-6;
    EXPECT_EQ(sim.bond_present_contacts(true), corner ? 2u : 1u) << (corner ? "corner" : "vertex");
    sim.advance();
    EXPECT_EQ(sim.wall_contacts().size(), corner ? 2u : 1u);
  }
}

// A sphere thrown sliding and spinning across a floor of 2 x 8 x 8 triangles follows the same
// path as on one quad: the tangential spring passes from element to element, so there is no
// snag. Tolerance: 1e-9 of the distance travelled (round-off of the different contact points).
TEST(MeshContact, SlidingAcrossTrianglesEqualsOnePlane) {
  auto run = [](const std::vector<Wall>& walls, int& max_contacts) {
    Simulation sim;
    Material m = elastic(1e5);
    m.restitution = m.restitution_t = 0.5;
    m.friction_angle = 20;
    sim.materials = MaterialTable({m}, {});
    sim.walls = walls;
    const double a = 0.004;
    sim.particles.add(0, Vec3(0.011, 0.013, a - 2.5e-7), a, 2500, 0);
    sim.particles.v[0] = Vec3(0.35, 0.21, 0);
    sim.particles.w[0] = Vec3(-20, 40, 5);
    sim.dt = 2e-6;
    max_contacts = 0;
    for (int s = 0; s < 100000; ++s) {
      sim.advance();
      max_contacts = std::max<int>(max_contacts, static_cast<int>(sim.wall_contacts().size()));
    }
    return sim.particles;
  };
  int n_mesh = 0, n_plane = 0;
  const Particles mesh = run(split_square(0.2, 8), n_mesh);
  const Particles plane = run({Wall{"plane", 0, box_face(Vec3(0, 0, -1), Vec3(0.2, 0.2, 0), 2, true), {}}}, n_plane);
  const double travelled = (mesh.x[0] - mesh.x_ref[0]).norm();
  std::printf("  sliding across 128 triangles: travelled %.4f m, |dx| = %.3g m, |dv| = %.3g m/s, |dw| = %.3g rad/s\n", travelled,
              (mesh.x[0] - plane.x[0]).norm(), (mesh.v[0] - plane.v[0]).norm(), (mesh.w[0] - plane.w[0]).norm());
  EXPECT_GT(travelled, 0.05) << "the sphere must cross many elements";
  EXPECT_EQ(n_mesh, 1) << "one contact at a time";
  EXPECT_LT((mesh.x[0] - plane.x[0]).norm(), 1e-9 * travelled);
  EXPECT_LT((mesh.v[0] - plane.v[0]).norm(), 1e-9 * plane.v[0].norm() + 1e-12);
  EXPECT_LT((mesh.w[0] - plane.w[0]).norm(), 1e-9 * plane.w[0].norm() + 1e-9);
}

// The binned wall search finds exactly the (particle, element) pairs within reach that a brute
// force over all elements finds, for a fine cylinder mesh and particles inside and outside it.
TEST(MeshContact, BinnedWallSearchEqualsBruteForce) {
  const int segments = 96, rings = 20;
  const double R = 0.05, H = 0.1;
  std::vector<WallGeometry> geometry;
  std::vector<Wall> walls;
  for (int s = 0; s < segments; ++s)
    for (int r = 0; r < rings; ++r) {
      auto at = [&](int ss, int rr) {
        const double t = 2 * std::numbers::pi * ss / segments;
        return Vec3(R * std::cos(t), R * std::sin(t), H * rr / rings);
      };
      walls.push_back(Wall{"c." + std::to_string(walls.size()), 0, {at(s, r), at(s + 1, r), at(s + 1, r + 1), at(s, r + 1)}, {}});
    }
  geometry.resize(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) place_wall(walls[w], 0, 0, geometry[w]);
  Particles p;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 3000; ++k) p.add(k, Vec3(0.06 * u(rng), 0.06 * u(rng), 0.05 + 0.06 * u(rng)), 0.002 + 0.002 * u(rng) * u(rng), 2500, 0);
  NeighbourList list;
  const double skin = 0.001;
  list.update(p, PeriodicBox{}, geometry, 0, skin);
  std::vector<std::pair<Index, Index>> want, got;
  for (std::size_t k = 0; k < p.size(); ++k)
    for (std::size_t w = 0; w < geometry.size(); ++w) {
      const double reach = p.radius[k] + skin;
      if ((closest_point(geometry[w], p.x[k]) - p.x[k]).squaredNorm() < reach * reach) want.emplace_back(p.id[k], w);
    }
  for (const FoundContact& f : list.wall_pairs()) got.emplace_back(f.key_i, f.key_j);
  std::printf("  %zu elements, %zu particles: %zu particle-element candidates\n", walls.size(), p.size(), want.size());
  EXPECT_GT(want.size(), 1000u);
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace dem
