#pragma once
// The particles' container (SPEC §9 step 3, `compact` and `[[stage.servo]]`): the convex region
// bounded by the planes of the walls. Box faces translate along their normals but keep their size,
// so once the side walls have moved in, the lid's polygon reaches beyond them and the bounding box
// of the walls' vertices no longer shrinks: neither tells the sample's volume or the area a wall
// actually presses on. The planes do.
//
// Two parts: plain convex geometry (half-spaces, polygon clipping, a convex polytope clipped plane
// by plane), and Container, which applies it to walls and particles at one moment.
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace dem {

struct Wall;
struct Particles;

using Polygon = std::vector<Vec3>;

// Area of a convex planar polygon [m^2] (0 for fewer than 3 vertices).
double polygon_area(const Polygon& v);

// The half-space {x : normal·x >= offset}; `normal` is a unit vector pointing into it.
struct HalfSpace {
  Vec3 normal = Vec3::UnitZ();
  double offset = 0;
  double distance(const Vec3& x) const { return normal.dot(x) - offset; }  // > 0 inside
  // The plane through `point` with unit normal `normal`.
  static HalfSpace through(const Vec3& point, const Vec3& normal) { return {normal, normal.dot(point)}; }
};

// The part of a convex planar polygon inside h (Sutherland–Hodgman against one plane). A vertex
// within `tol` of the plane counts as on it: it is kept and never split, so a polygon lying in the
// plane, or touching it, comes back unchanged. The result is convex, in the same order (empty if
// nothing is inside).
Polygon clip_polygon(const Polygon& poly, const HalfSpace& h, double tol);

// The part of convex planar polygon `poly` inside convex polygon `window` (which should lie in the
// same plane; it is clipped by the planes through the window's edges, normal to the window).
Polygon clip_polygon_to(const Polygon& poly, const Polygon& window);

// A bounded convex polytope as the list of its faces, each a convex polygon whose vertices run
// counter-clockwise seen from outside. Starts as an axis-aligned box and is cut by half-spaces.
class ConvexPolytope {
 public:
  ConvexPolytope(const Vec3& lo, const Vec3& hi);  // the box [lo, hi]; every component of hi > lo
  // Keeps the part inside h: faces are clipped and the cut closed by a new face in h's plane.
  // Vertices within 1e-9 of the box diagonal of the plane count as on it (a plane through a face
  // changes nothing). Cutting everything away leaves an empty polytope.
  void clip(const HalfSpace& h);
  double volume() const;                      // [m^3]; 0 if empty
  bool empty() const { return faces_.empty(); }
  const std::vector<Polygon>& faces() const { return faces_; }
  // The face lying in h's plane (every vertex within the tolerance), or an empty polygon.
  Polygon face_in(const HalfSpace& h) const;

 private:
  std::vector<Polygon> faces_;
  double tol_;
};

// The container of the particles at one moment, from the walls at time t and the particles' centres
// and radii. Every wall's plane is taken with its normal turned towards the centroid of the centres;
// a plane bounds the container only if every centre lies on that side of it (on it counts), so
// walls inside the sample (a baffle, a helical ramp, a hopper the bed has flowed out of) cut
// nothing. The container is the bounding box of all walls' vertices cut by the bounding planes and,
// under gravity, by the plane normal to gravity through the top of the highest sphere (so an open
// box, or a lid far above the bed, does not count the empty headspace).
//
// Meant for convex containers (boxes, cylinders, prisms); it does not change the walls. Cost: the
// centroid and top of the spheres, then per plane one pass over the centres when it matters.
class Container {
 public:
  Container(const std::vector<Wall>& walls, double t, const Particles& p, const Vec3& gravity);

  // Volume of the container [m^3] (0 without walls or particles).
  double volume();
  // The area of wall k's polygon inside the container [m^2]: for a box face, the face of the
  // container in that plane within the face's quad, so a lid between side walls moved in counts only
  // the cross-section between them. The same as the face of the polytope in the wall's plane
  // intersected with the wall's polygon, computed by clipping the polygon by only the planes that
  // cut it. A wall wholly above the spheres (a lid not yet down) keeps its area between the walls;
  // a wall wholly outside the others' planes keeps its own area.
  double wall_area(std::size_t k);

 private:
  const std::vector<Wall>& walls_;
  double t_;
  const Particles& particles_;
  Vec3 centroid_ = Vec3::Zero();
  Vec3 lo_ = Vec3::Constant(INFINITY), hi_ = Vec3::Constant(-INFINITY);  // the centres' box
  bool has_top_ = false;  // under gravity, with particles
  HalfSpace top_;         // below the top of the highest sphere
  std::vector<signed char> bounds_;  // per wall: -1 not yet known, 0 no, 1 yes
  std::vector<HalfSpace> planes_;    // per wall, once asked for (a servo group asks for every wall
  std::vector<char> have_plane_;     // per element of the group)

  Polygon vertices(std::size_t k) const;
  const HalfSpace& plane(std::size_t k);  // wall k's plane, normal towards the centroid
  bool bounds(std::size_t k);
};

}  // namespace dem
