#include "walls/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace dem {

namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("wall mesh: ") + what);
}

bool finite(const Vec3& v) { return v.allFinite(); }

// Right-handed orthonormal frame (e1, e2, e3) with e3 along `axis` (see the header for e1).
struct Frame {
  Vec3 e1, e2, e3;
};

Frame frame_about(const Vec3& axis) {
  require(finite(axis) && axis.norm() > 0, "the axis (or normal) must be a finite non-zero vector");
  Frame f;
  f.e3 = axis.normalized();
  // x unless the axis is within acos(0.9) ≈ 26° of it, where the projection would be short.
  const Vec3 helper = std::abs(f.e3.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  f.e1 = (helper - helper.dot(f.e3) * f.e3).normalized();
  f.e2 = f.e3.cross(f.e1);
  return f;
}

// Unit directions of the n ring vertices at angles 2πk/n, computed once per k: every ring of a
// mesh built from them places vertex k on the same ray, and index n wraps to 0 (closed ring).
std::vector<Vec3> ring_directions(const Frame& f, int n) {
  std::vector<Vec3> d(n);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    d[k] = std::cos(t) * f.e1 + std::sin(t) * f.e2;
  }
  return d;
}

void require_segments(int n) { require(n >= 3, "at least 3 segments are needed around a circle"); }

}  // namespace

std::vector<Polygon> rectangle_mesh(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, int nu, int nv,
                                    bool triangles) {
  require(finite(corner) && finite(edge_u) && finite(edge_v), "the rectangle's corner and edges must be finite");
  require(edge_u.cross(edge_v).norm() > 1e-12 * edge_u.norm() * edge_v.norm() && edge_u.norm() > 0 && edge_v.norm() > 0,
          "the rectangle's edges must be non-zero and not parallel");
  require(nu >= 1 && nv >= 1, "a rectangle needs at least 1 division along each edge");
  // Grid nodes computed once; node (i, j) = corner + (i/nu)·edge_u + (j/nv)·edge_v.
  std::vector<Vec3> node(static_cast<std::size_t>(nu + 1) * (nv + 1));
  auto at = [&](int i, int j) -> Vec3& { return node[static_cast<std::size_t>(j) * (nu + 1) + i]; };
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) at(i, j) = corner + (double(i) / nu) * edge_u + (double(j) / nv) * edge_v;
  std::vector<Polygon> out;
  out.reserve(static_cast<std::size_t>(nu) * nv * (triangles ? 2 : 1));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Vec3 &a = at(i, j), &b = at(i + 1, j), &c = at(i + 1, j + 1), &d = at(i, j + 1);
      if (triangles) {
        out.push_back({a, b, c});
        out.push_back({a, c, d});
      } else {
        out.push_back({a, b, c, d});
      }
    }
  return out;
}

std::vector<Polygon> cylinder_mesh(const Vec3& base_centre, const Vec3& axis, double radius, double height, int segments,
                                   int rings) {
  require(finite(base_centre), "the base centre must be finite");
  require(std::isfinite(radius) && radius > 0, "the cylinder's radius must be > 0");
  require(std::isfinite(height) && height > 0, "the cylinder's height must be > 0");
  require_segments(segments);
  require(rings >= 1, "a cylinder needs at least 1 ring");
  const Frame f = frame_about(axis);
  const std::vector<Vec3> dir = ring_directions(f, segments);
  // Vertex (ring level j, segment k), each computed once.
  std::vector<Vec3> p(static_cast<std::size_t>(rings + 1) * segments);
  auto at = [&](int j, int k) -> Vec3& { return p[static_cast<std::size_t>(j) * segments + (k % segments)]; };
  for (int j = 0; j <= rings; ++j) {
    const Vec3 c = base_centre + (height * j / rings) * f.e3;
    for (int k = 0; k < segments; ++k) at(j, k) = c + radius * dir[k];
  }
  std::vector<Polygon> out;
  out.reserve(static_cast<std::size_t>(rings) * segments);
  for (int j = 0; j < rings; ++j)
    for (int k = 0; k < segments; ++k) out.push_back({at(j, k), at(j, k + 1), at(j + 1, k + 1), at(j + 1, k)});
  return out;
}

std::vector<Polygon> disc_mesh(const Vec3& centre, const Vec3& normal, double radius, double inner_radius, int segments) {
  require(finite(centre), "the disc's centre must be finite");
  require(std::isfinite(radius) && radius > 0, "the disc's radius must be > 0");
  require(std::isfinite(inner_radius) && inner_radius >= 0 && inner_radius < radius,
          "the disc's inner radius must be in [0, radius)");
  require_segments(segments);
  const Frame f = frame_about(normal);
  const std::vector<Vec3> dir = ring_directions(f, segments);
  std::vector<Vec3> outer(segments), inner(segments);
  for (int k = 0; k < segments; ++k) {
    outer[k] = centre + radius * dir[k];
    inner[k] = centre + inner_radius * dir[k];
  }
  std::vector<Polygon> out;
  out.reserve(segments);
  for (int k = 0; k < segments; ++k) {
    const int k1 = (k + 1) % segments;
    if (inner_radius == 0) out.push_back({centre, outer[k], outer[k1]});
    else out.push_back({inner[k], outer[k], outer[k1], inner[k1]});
  }
  return out;
}

std::vector<Polygon> cone_mesh(const Vec3& base_centre, const Vec3& axis, double radius_base, double radius_top,
                               double height, int segments) {
  require(finite(base_centre), "the cone's base centre must be finite");
  require(std::isfinite(radius_base) && std::isfinite(radius_top) && radius_base >= 0 && radius_top >= 0,
          "the cone's radii must be >= 0");
  require(radius_base > 0 || radius_top > 0, "at least one of the cone's radii must be > 0");
  require(std::isfinite(height) && height > 0, "the cone's height must be > 0");
  require_segments(segments);
  const Frame f = frame_about(axis);
  const std::vector<Vec3> dir = ring_directions(f, segments);
  const Vec3 top_centre = base_centre + height * f.e3;
  std::vector<Vec3> bot(segments), top(segments);
  for (int k = 0; k < segments; ++k) {
    bot[k] = base_centre + radius_base * dir[k];
    top[k] = top_centre + radius_top * dir[k];
  }
  std::vector<Polygon> out;
  out.reserve(segments);
  for (int k = 0; k < segments; ++k) {
    const int k1 = (k + 1) % segments;
    // The chord at the base and the chord at the top are parallel (both along dir[k1] − dir[k]),
    // so the four points are coplanar: a trapezoid, or a triangle where a radius is zero.
    if (radius_top == 0) out.push_back({bot[k], bot[k1], top_centre});
    else if (radius_base == 0) out.push_back({base_centre, top[k1], top[k]});
    else out.push_back({bot[k], bot[k1], top[k1], top[k]});
  }
  return out;
}

namespace {
// Angular steps of a helix: the small allowance keeps a turns·segments_per_turn that is an integer
// up to round-off from gaining a step.
double helix_steps(double turns, int segments_per_turn) {
  return std::max(1.0, std::ceil(turns * segments_per_turn - 1e-9));
}
}  // namespace

long long helical_ramp_elements(double turns, int segments_per_turn, int radial_segments) {
  const double n = 2 * helix_steps(turns, segments_per_turn) * std::max(1, radial_segments);
  return n < 1e15 ? static_cast<long long>(n) : static_cast<long long>(1e15);
}

std::vector<Polygon> helical_ramp_mesh(const Vec3& base_centre, const Vec3& axis, double inner_radius,
                                       double outer_radius, double pitch, double turns, int segments_per_turn,
                                       int radial_segments) {
  require(finite(base_centre), "the helix's base centre must be finite");
  require(std::isfinite(outer_radius) && outer_radius > 0, "the helix's outer radius must be > 0");
  require(std::isfinite(inner_radius) && inner_radius >= 0 && inner_radius < outer_radius,
          "the helix's inner radius must be in [0, outer radius)");
  require(std::isfinite(pitch) && pitch != 0, "the helix's pitch must be non-zero");
  require(std::isfinite(turns) && turns > 0, "the helix's number of turns must be > 0");
  require(segments_per_turn >= 3, "a helix needs at least 3 segments per turn");
  require(radial_segments >= 1, "a helix needs at least 1 radial segment");
  const Frame f = frame_about(axis);
  const long long n = static_cast<long long>(helix_steps(turns, segments_per_turn));
  const int m = radial_segments;
  // Vertex (step k = 0..n, radius j = 0..m), each computed once.
  std::vector<Vec3> p(static_cast<std::size_t>(n + 1) * (m + 1));
  auto at = [&](long long k, int j) -> Vec3& { return p[static_cast<std::size_t>(k) * (m + 1) + j]; };
  for (long long k = 0; k <= n; ++k) {
    const double frac = double(k) / double(n);  // of the whole strip
    const double theta = 2 * std::numbers::pi * turns * frac;
    const Vec3 d = std::cos(theta) * f.e1 + std::sin(theta) * f.e2;
    const Vec3 c = base_centre + (pitch * turns * frac) * f.e3;  // height pitch·θ/(2π)
    for (int j = 0; j <= m; ++j) {
      const double r = j == m ? outer_radius : inner_radius + (outer_radius - inner_radius) * j / m;
      at(k, j) = c + r * d;
    }
  }
  std::vector<Polygon> out;
  out.reserve(2 * static_cast<std::size_t>(n) * m);
  for (long long k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j) {
      out.push_back({at(k, j), at(k, j + 1), at(k + 1, j + 1)});
      out.push_back({at(k, j), at(k + 1, j + 1), at(k + 1, j)});
    }
  return out;
}

}  // namespace dem
