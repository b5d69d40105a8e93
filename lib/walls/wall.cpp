#include "walls/wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace dem {

bool WallMotion::moves() const {
  return velocity != Vec3::Zero() || !table_time.empty() || amplitude != 0 || angular_speed != 0;
}

namespace {
// The table segment holding s: the last k with table_time[k] <= s (0 before the table).
std::size_t table_segment(const std::vector<double>& time, double s) {
  const auto it = std::upper_bound(time.begin(), time.end(), s);
  return it == time.begin() ? 0 : static_cast<std::size_t>(it - time.begin()) - 1;
}
}  // namespace

Vec3 WallMotion::offset(double t) const {
  const double s = t - t0;
  Vec3 d = velocity * s;
  if (!table_time.empty() && s > 0) {
    const std::size_t k = table_segment(table_time, s);
    if (k + 1 >= table_time.size()) {
      d += table_offset.back();  // held after the last row
    } else {
      const double u = (s - table_time[k]) / (table_time[k + 1] - table_time[k]);
      d += table_offset[k] + u * (table_offset[k + 1] - table_offset[k]);
    }
  }
  if (amplitude != 0) d += direction * (amplitude * std::sin(2 * std::numbers::pi * frequency * s));
  return d;
}

Vec3 WallMotion::velocity_at(double t) const {
  const double s = t - t0;
  Vec3 v = velocity;
  if (!table_time.empty() && s >= 0) {
    const std::size_t k = table_segment(table_time, s);
    if (k + 1 < table_time.size()) v += (table_offset[k + 1] - table_offset[k]) / (table_time[k + 1] - table_time[k]);
  }
  if (amplitude != 0) {
    const double om = 2 * std::numbers::pi * frequency;
    v += direction * (amplitude * om * std::cos(om * s));
  }
  return v;
}

Eigen::Matrix3d WallMotion::rotation(double t) const {
  if (angular_speed == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle(t), axis).toRotationMatrix();
}

Vec3 WallMotion::place(const Vec3& x0, double t) const {
  if (angular_speed == 0) return x0 + offset(t);
  return centre + offset(t) + rotation(t) * (x0 - centre);
}

std::vector<Vec3> Wall::vertices_at(double t) const {
  std::vector<Vec3> out(base);
  for (Vec3& v : out) v = motion.place(v, t);
  return out;
}

void Wall::start_motion(const WallMotion& m, double t) {
  base = vertices_at(t);
  motion = m;
  motion.t0 = t;
}

void place_wall(const Wall& w, double t, double dt, WallGeometry& g, RotationCache& rotations) {
  const WallMotion& m = w.motion;
  g.material = w.material;
  const int count = static_cast<int>(w.base.size());
  const bool new_base = g.count != count || !std::equal(w.base.begin(), w.base.end(), g.base.begin());
  if (new_base) {  // a new element, or a stage's motion started from where the last one left it
    g.count = count;
    std::copy(w.base.begin(), w.base.end(), g.base.begin());
    g.base_normal = (g.base[1] - g.base[0]).cross(g.base[2] - g.base[0]).normalized();
    inward_normals(g.base.data(), count, g.base_normal, g.base_inward.data());
  }
  // A fixed element placed before stays where it is (a 10,000-triangle floor is not copied each
  // step).
  if (!m.moves() && !new_base && g.velocity == Vec3::Zero() && g.spin == Vec3::Zero() &&
      std::equal(g.base.begin(), g.base.begin() + count, g.vertices.begin()))
    return;
  const Vec3 d = m.offset(t);
  if (m.rotates()) {  // x = c + d + R (x0 - c); a direction turns with R alone
    const Eigen::Matrix3d& r = rotations.rotation(m, t);
    for (int v = 0; v < count; ++v) g.vertices[v] = m.centre + d + r * (g.base[v] - m.centre);
    g.normal = r * g.base_normal;
    for (int k = 0; k < count; ++k) g.inward[k] = r * g.base_inward[k];
  } else {
    for (int v = 0; v < count; ++v) g.vertices[v] = g.base[v] + d;
    g.normal = g.base_normal;
    g.inward = g.base_inward;
  }
  // At t^{n-1/2}, the time of the particles' velocities it is compared with (eq. 2.18).
  g.velocity = m.velocity_at(t - 0.5 * dt);
  g.spin = m.angular_speed * m.axis;
  g.centre = m.centre + d;
}

namespace {
Vec3 closest_on_segment(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  double s = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return a + s * ab;
}

// eq. 2.4-2.5 with the edges' inward normals (inward_normals): the projection q on the plane if it
// lies on the inner side of every edge, else the nearest point of the edges it lies outside of. In
// a convex polygon the nearest point of the boundary lies on such an edge (docs/physics.md, P21),
// so the others need no search.
Vec3 closest_point_with(const Vec3* v, const Vec3* inward, int n, const Vec3& nrm, const Vec3& p) {
  const Vec3 q = p - (p - v[0]).dot(nrm) * nrm;  // projection on the plane
  int outside = 0;                                // a bit per edge
  for (int k = 0; k < n; ++k) outside |= int((q - v[k]).dot(inward[k]) < 0) << k;
  if (!outside) return q;
  Vec3 best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n; ++k) {
    if (!(outside >> k & 1)) continue;
    const Vec3 c = closest_on_segment(v[k], v[k + 1 < n ? k + 1 : 0], p);
    const double d2 = (c - p).squaredNorm();
    if (d2 < best_d2) best = c, best_d2 = d2;
  }
  return best;
}
}  // namespace

void inward_normals(const Vec3* v, int n, const Vec3& nrm, Vec3* inward) {
  for (int k = 0; k < n; ++k) inward[k] = nrm.cross(v[k + 1 < n ? k + 1 : 0] - v[k]);
}

Vec3 closest_point_on_polygon(const Vec3* v, int n, const Vec3& nrm, const Vec3& p) {
  std::array<Vec3, 4> inward;
  inward_normals(v, n, nrm, inward.data());
  return closest_point_with(v, inward.data(), n, nrm, p);
}

Vec3 closest_point(const WallGeometry& g, const Vec3& p) {
  return closest_point_with(g.vertices.data(), g.inward.data(), g.count, g.normal, p);
}

std::vector<Vec3> box_face(const Vec3& lo, const Vec3& hi, int axis, bool max_side) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::vector<Vec3> quad;
  for (const auto& [su, sv] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
    Vec3 p;
    p[axis] = max_side ? hi[axis] : lo[axis];
    p[u] = su ? hi[u] : lo[u];
    p[v] = sv ? hi[v] : lo[v];
    quad.push_back(p);
  }
  return quad;
}

std::string polygon_problem(const std::vector<Vec3>& v) {
  if (v.size() != 3 && v.size() != 4) return "a wall polygon needs 3 or 4 vertices";
  const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
  const double scale = std::max((v[1] - v[0]).norm(), (v[2] - v[0]).norm());
  if (!(n.norm() > 1e-12 * scale * scale) || !(scale > 0)) return "the vertices are collinear or coincident";
  const Vec3 u = n.normalized();
  const int m = static_cast<int>(v.size());
  for (int k = 0; k < m; ++k) {
    if (std::abs((v[k] - v[0]).dot(u)) > 1e-9 * scale) return "the vertices are not in one plane";
    const Vec3& a = v[k];
    const Vec3& b = v[(k + 1) % m];
    const Vec3& c = v[(k + 2) % m];
    if ((b - a).cross(c - b).dot(u) <= 0) return "the polygon is not convex (or its vertices are not in order)";
  }
  return "";
}

}  // namespace dem
