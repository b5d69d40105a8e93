#pragma once
// Regions of space for cutting a model (SPEC §9 step 4: "other shapes come from a box by cutting:
// remove particles inside or outside a region (a cylinder for a borehole, a half-space, a mesh)").
// Used by the stage action `remove` and by `[[generation.cut]]`; a particle belongs to a region
// when its centre does.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dem {

// A closed triangle surface for inside tests. Closed means every edge is shared by exactly two
// triangles that run along it in opposite directions (a consistently oriented, watertight, manifold
// surface); vertices are matched by exact coordinates, as an STL file repeats them.
class ClosedMesh {
 public:
  // Throws std::invalid_argument saying what is wrong (an open edge, an edge of three or more
  // triangles, triangles facing opposite ways across an edge), with the edge's end points.
  explicit ClosedMesh(std::vector<std::array<Vec3, 3>> triangles);

  // The generalized winding number of the surface about x: the sum of the solid angles of the
  // triangles seen from x over 4π (van Oosterom and Strackee's formula for a triangle's solid
  // angle). For a closed surface it is ±1 inside and 0 outside (the sign by orientation), exactly
  // but for round-off, wherever the point is: no ray to aim, no edge or vertex to hit.
  double winding_number(const Vec3& x) const;
  // Inside: |winding number| > 1/2. Points outside the triangles' bounding box are outside at once.
  bool contains(const Vec3& x) const;
  // Volume enclosed (divergence theorem), positive whichever way the triangles face [m^3].
  double volume() const;
  std::size_t size() const { return triangles_.size(); }
  void bounds(Vec3& lo, Vec3& hi) const { lo = lo_, hi = hi_; }  // of the triangles' vertices

 private:
  std::vector<std::array<Vec3, 3>> triangles_;
  Vec3 lo_, hi_;  // bounding box
};

struct Region {
  enum class Kind { Box, Sphere, Cylinder, HalfSpace, Mesh };
  Kind kind = Kind::Box;
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();  // box
  Vec3 centre = Vec3::Zero();                   // sphere; cylinder: a point on the axis, the middle when length is given
  double radius = 0;                            // sphere, cylinder [m]
  Vec3 axis = Vec3::UnitZ();                    // cylinder: unit axis
  double length = 0;                            // cylinder: 0 = infinite, else its length along the axis [m]
  Vec3 point = Vec3::Zero();                    // half-space: a point of its plane
  Vec3 normal = Vec3::UnitZ();                  // half-space: unit normal, pointing into the region
  std::shared_ptr<const ClosedMesh> mesh;       // mesh (shared: a scene's specs are copied)

  // Is x inside? The boundary counts as inside (box, sphere, cylinder, half-space); for a mesh a
  // point on the surface itself may fall either way.
  bool contains(const Vec3& x) const;
  // Does any of the points lie inside (contains(), its kind chosen once for them all)?
  bool any_inside(const std::vector<Vec3>& x) const;
};

}  // namespace dem
