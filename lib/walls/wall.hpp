#pragma once
// Rigid planar walls: convex triangles or quadrilaterals (SPEC §3). Motion is prescribed, not
// integrated, so a wall's position is a closed-form function of time (exact on restart).
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dem {

struct WallMotion {
  enum class Kind { Fixed, Translate, Vibrate };
  Kind kind = Kind::Fixed;
  Vec3 velocity = Vec3::Zero();   // Translate: constant velocity [m/s]
  Vec3 direction = Vec3::UnitZ(); // Vibrate: unit direction
  double frequency = 0;           // Vibrate: [Hz]
  double amplitude = 0;           // Vibrate: displacement amplitude [m]
  double t0 = 0;                  // time at which the motion starts [s]

  Vec3 offset(double t) const;        // displacement from the base position at time t
  Vec3 velocity_at(double t) const;   // d offset / dt
};

struct Wall {
  std::string name;
  int material = 0;
  std::vector<Vec3> base;  // vertices when the current motion started, 3 or 4, convex, planar
  WallMotion motion;

  std::vector<Vec3> vertices_at(double t) const;
  // Bake the current offset into the base and start a new motion at time t (stage change).
  void start_motion(const WallMotion& m, double t);
};

// A wall's current vertices, plane normal and velocity, computed once per step.
struct WallGeometry {
  std::vector<Vec3> vertices;
  Vec3 normal;
  Vec3 velocity;  // at t^{n-1/2}, like the particles' velocities
};

// Closest point of a wall's current polygon to p (the overload below, on its geometry).
Vec3 closest_point(const WallGeometry& g, const Vec3& p);

// Closest point of a convex planar polygon to p (eq. 2.4-2.5: projection if inside, else the
// nearest point of the boundary: edge or vertex). `unit_normal` is the polygon's plane normal.
Vec3 closest_point_on_polygon(const Vec3* verts, int n_verts, const Vec3& unit_normal, const Vec3& p);

// The quad of an axis-aligned box on face `axis` (0 x, 1 y, 2 z) at its min or max side,
// vertices in order (a convex planar polygon).
std::vector<Vec3> box_face(const Vec3& lo, const Vec3& hi, int axis, bool max_side);

// Checks that the vertices form a non-degenerate convex planar polygon; returns an empty string
// if fine, otherwise what is wrong.
std::string polygon_problem(const std::vector<Vec3>& verts);

}  // namespace dem
