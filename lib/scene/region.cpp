#include "scene/region.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace dem {

namespace {

// Vertices are matched by exact coordinates (an STL file repeats them bit for bit).
using Key = std::tuple<double, double, double>;
Key key_of(const Vec3& v) { return {v[0], v[1], v[2]}; }

std::string point_text(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return s.str();
}

}  // namespace

ClosedMesh::ClosedMesh(std::vector<std::array<Vec3, 3>> triangles) : triangles_(std::move(triangles)) {
  if (triangles_.empty()) throw std::invalid_argument("the mesh has no triangles");
  // Number the distinct vertices, then count each edge's uses: +1 along a -> b with a < b, -1
  // along b -> a. A closed, consistently oriented surface uses every edge once each way.
  std::map<Key, int> index;
  std::vector<Vec3> where;
  auto id = [&](const Vec3& v) {
    const auto [it, added] = index.emplace(key_of(v), static_cast<int>(where.size()));
    if (added) where.push_back(v);
    return it->second;
  };
  struct Use {
    int count = 0, direction = 0;
  };
  std::map<std::pair<int, int>, Use> edges;
  lo_ = hi_ = triangles_[0][0];
  for (const auto& t : triangles_) {
    const int v[3] = {id(t[0]), id(t[1]), id(t[2])};
    for (int e = 0; e < 3; ++e) {
      const int a = v[e], b = v[(e + 1) % 3];
      if (a == b) throw std::invalid_argument("a triangle has two equal vertices at " + point_text(t[e]));
      Use& u = edges[{std::min(a, b), std::max(a, b)}];
      ++u.count;
      u.direction += a < b ? 1 : -1;
      lo_ = lo_.cwiseMin(t[e]), hi_ = hi_.cwiseMax(t[e]);
    }
  }
  std::size_t open = 0, shared = 0, flipped = 0;
  std::pair<int, int> first_open{-1, -1}, first_shared{-1, -1}, first_flipped{-1, -1};
  for (const auto& [e, u] : edges) {
    if (u.count == 1 && open++ == 0) first_open = e;
    if (u.count > 2 && shared++ == 0) first_shared = e;
    if (u.count == 2 && u.direction != 0 && flipped++ == 0) first_flipped = e;
  }
  auto edge_text = [&](const std::pair<int, int>& e) { return "between " + point_text(where[e.first]) + " and " + point_text(where[e.second]); };
  if (open > 0)
    throw std::invalid_argument("the mesh is not closed: " + std::to_string(open) + " edges belong to one triangle only (the first " +
                                edge_text(first_open) + "); an inside test needs a watertight surface whose triangles share " +
                                "their vertices exactly");
  if (shared > 0)
    throw std::invalid_argument("the mesh is not a simple closed surface: " + std::to_string(shared) +
                                " edges belong to three or more triangles (the first " + edge_text(first_shared) + ")");
  if (flipped > 0)
    throw std::invalid_argument("the mesh's triangles are not consistently oriented: across " + std::to_string(flipped) +
                                " edges the two triangles face opposite ways (the first " + edge_text(first_flipped) +
                                "); every triangle must run the same way (all normals outward, or all inward)");
}

double ClosedMesh::winding_number(const Vec3& x) const {
  // Solid angle of triangle (a, b, c) seen from x, with a, b, c taken from x (van Oosterom and
  // Strackee 1983): tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|). atan2 keeps
  // the sign (the orientation) and the quadrant.
  double sum = 0;
  for (const auto& t : triangles_) {
    const Vec3 a = t[0] - x, b = t[1] - x, c = t[2] - x;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double det = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    sum += 2 * std::atan2(det, den);
  }
  return sum / (4 * std::numbers::pi);
}

bool ClosedMesh::contains(const Vec3& x) const {
  if ((x.array() < lo_.array()).any() || (x.array() > hi_.array()).any()) return false;
  return std::abs(winding_number(x)) > 0.5;
}

double ClosedMesh::volume() const {
  double six = 0;
  for (const auto& t : triangles_) six += (t[0] - lo_).dot((t[1] - lo_).cross(t[2] - lo_));
  return std::abs(six) / 6;
}

namespace {

// Calls f with the inside test of r's kind (a callable on a point), chosen once: contains() takes
// it for one point, any_inside() for many.
template <class F>
bool with_inside_test(const Region& r, F f) {
  switch (r.kind) {
    case Region::Kind::Box:
      return f([&](const Vec3& x) { return (x.array() >= r.min.array()).all() && (x.array() <= r.max.array()).all(); });
    case Region::Kind::Sphere: return f([&](const Vec3& x) { return (x - r.centre).squaredNorm() <= r.radius * r.radius; });
    case Region::Kind::Cylinder:
      return f([&](const Vec3& x) {
        const Vec3 d = x - r.centre;
        const double along = d.dot(r.axis);
        return !(r.length > 0 && std::abs(along) > 0.5 * r.length) && (d - along * r.axis).squaredNorm() <= r.radius * r.radius;
      });
    case Region::Kind::HalfSpace: return f([&](const Vec3& x) { return (x - r.point).dot(r.normal) >= 0; });
    case Region::Kind::Mesh: return f([&](const Vec3& x) { return r.mesh->contains(x); });
  }
  return false;
}

}  // namespace

bool Region::contains(const Vec3& x) const {
  return with_inside_test(*this, [&](auto inside) { return inside(x); });
}

bool Region::any_inside(const std::vector<Vec3>& x) const {
  const long n = static_cast<long>(x.size());
  return with_inside_test(*this, [&](auto inside) {
    int found = 0;  // no early exit: the loop stays one plain pass
#pragma omp parallel for schedule(static) reduction(| : found) if (n > 16384)
    for (long k = 0; k < n; ++k) found |= inside(x[k]);
    return found != 0;
  });
}

}  // namespace dem
