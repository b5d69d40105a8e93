#pragma once
// Rigid walls made of convex planar elements: triangles or quadrilaterals (docs/physics.md eq. P21-P23). A mesh wall
// (cylinder, cone, STL, ...) is many elements sharing one motion. Motion is prescribed, not
// integrated, so an element's position is a closed-form function of time (exact on restart).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dem {

// A rigid motion from time t0, the composition of a translation (constant velocity and/or a time
// table of displacements), a harmonic vibration and a rotation about an axis:
//   x(t) = c + d(s) + R(ω s)·(x0 − c),   s = t − t0,
//   d(s) = u·s + table(s) + e·A·sin(2π f s).
// The rotation axis (through c, direction a) travels with the translation and the vibration, so a
// drum can rotate and vibrate at once. The velocity of the wall material at a point x is
//   v(x) = d'(s) + ω a × (x − c − d(s))   (eq. 2.18 uses it at the contact point).
struct WallMotion {
  Vec3 velocity = Vec3::Zero();      // translation: constant velocity u [m/s]
  std::vector<double> table_time;    // translation table: times since t0 [s], increasing from 0
  std::vector<Vec3> table_offset;    // displacements at those times [m] (linear in between, held after)
  Vec3 direction = Vec3::UnitZ();    // vibration: unit direction e
  double frequency = 0;              // vibration: f [Hz]
  double amplitude = 0;              // vibration: displacement amplitude A [m]
  Vec3 centre = Vec3::Zero();        // rotation: a point c on the axis [m]
  Vec3 axis = Vec3::UnitZ();         // rotation: unit axis a (right-hand rule)
  double angular_speed = 0;          // rotation: ω [rad/s]
  double t0 = 0;                     // time at which the motion starts [s]

  bool moves() const;
  bool rotates() const { return angular_speed != 0; }
  Vec3 offset(double t) const;                 // d(s): the displacement of the axis point c
  Vec3 velocity_at(double t) const;            // d'(s)
  double angle(double t) const { return angular_speed * (t - t0); }  // ω s [rad]
  Eigen::Matrix3d rotation(double t) const;    // R(ω s)
  Vec3 place(const Vec3& x0, double t) const;  // x(t) of the material point at x0 when the motion started
};

struct Wall {
  std::string name;
  int material = 0;
  std::vector<Vec3> base;  // vertices when the current motion started, 3 or 4, convex, planar
  WallMotion motion;

  std::vector<Vec3> vertices_at(double t) const;
  // Bake the current position into the base and start a new motion at time t (stage change).
  void start_motion(const WallMotion& m, double t);
};

// An element's current vertices, plane normal and velocity field, computed once per step without
// allocation (the force loop reads it).
struct WallGeometry {
  std::array<Vec3, 4> vertices;
  int count = 0;               // 3 or 4 vertices
  Vec3 normal = Vec3::UnitZ();
  std::array<Vec3, 4> inward;  // per edge (vertex k to the next): normal x edge, into the polygon
  Vec3 velocity = Vec3::Zero();  // of the axis point, at t^{n-1/2} like the particles' velocities
  Vec3 spin = Vec3::Zero();      // ω a [rad/s]
  Vec3 centre = Vec3::Zero();    // the axis point c + d now [m]
  int material = 0;              // the wall's (Wall::material), read here where the contact's geometry is in cache
  // The element where its motion started (Wall::base) and that frame's normal and inward normals,
  // worked out once per base: a rigid motion carries them (rotates or keeps them), so a step places
  // a moving element without a square root, a division or a cross product (eq. P22).
  std::array<Vec3, 4> base;
  Vec3 base_normal = Vec3::UnitZ();
  std::array<Vec3, 4> base_inward;
  // velocity + spin x (x - centre), written out by component: the same operations as Eigen's
  // cross product and sum, kept in registers (Eigen's went through memory, stored a double at a time
  // and read back two at a time: a stalled store forwarding per wall contact).
  Vec3 velocity_of(const Vec3& x) const {
    const double rx = x.x() - centre.x(), ry = x.y() - centre.y(), rz = x.z() - centre.z();
    return Vec3(velocity.x() + (spin.y() * rz - spin.z() * ry), velocity.y() + (spin.z() * rx - spin.x() * rz),
                velocity.z() + (spin.x() * ry - spin.y() * rx));
  }
};

// The rotation of the last motion asked for: a mesh's elements share one motion, so placing them
// works out its sine and cosine once, not once per element. The same matrix as WallMotion::rotation.
class RotationCache {
 public:
  const Eigen::Matrix3d& rotation(const WallMotion& m, double t) {
    const double a = m.angle(t);
    if (!(a == angle_ && m.axis == axis_)) angle_ = a, axis_ = m.axis, r_ = m.rotation(t);
    return r_;
  }

 private:
  double angle_ = std::numeric_limits<double>::quiet_NaN();  // none yet
  Vec3 axis_ = Vec3::Zero();
  Eigen::Matrix3d r_ = Eigen::Matrix3d::Identity();
};

// Fills g with wall w at time t; velocities at t - dt/2 (the particles' half step). `rotations`
// serves the elements placed one after another (a thread's own).
void place_wall(const Wall& w, double t, double dt, WallGeometry& g, RotationCache& rotations);
inline void place_wall(const Wall& w, double t, double dt, WallGeometry& g) {
  RotationCache rotations;
  place_wall(w, t, dt, g, rotations);
}

// Closest point of a wall's current polygon to p (the overload below, on its geometry).
Vec3 closest_point(const WallGeometry& g, const Vec3& p);

// Closest point of a convex planar polygon to p (eq. 2.4-2.5: projection if inside, else the
// nearest point of the boundary: edge or vertex). `unit_normal` is the polygon's plane normal.
Vec3 closest_point_on_polygon(const Vec3* verts, int n_verts, const Vec3& unit_normal, const Vec3& p);

// Per edge k of a polygon (vertex k to the next): unit_normal x edge, which points into the polygon
// (vertices counter-clockwise about the normal). A point q of the plane lies inside where
// (q - v_k) . inward_k >= 0 for every edge: the triple product of the edge, q - v_k and the normal
// with the edge's part computed once per element (closest_point took 13 ns, most of it those
// cross products, and a settling box asks for one per wall contact and step).
void inward_normals(const Vec3* verts, int n_verts, const Vec3& unit_normal, Vec3* inward);

// The quad of an axis-aligned box on face `axis` (0 x, 1 y, 2 z) at its min or max side,
// vertices in order (a convex planar polygon).
std::vector<Vec3> box_face(const Vec3& lo, const Vec3& hi, int axis, bool max_side);

// Checks that the vertices form a non-degenerate convex planar polygon; returns an empty string
// if fine, otherwise what is wrong.
std::string polygon_problem(const std::vector<Vec3>& verts);

}  // namespace dem
