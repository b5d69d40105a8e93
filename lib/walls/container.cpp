#include "walls/container.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

namespace {

// Newell's normal of a polygon (not normalised): robust for any planar polygon, whichever three
// vertices are nearly collinear. Counter-clockwise about it.
template <class Points>
Vec3 newell_normal(const Points& v, std::size_t n) {
  Vec3 s = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) s += v[i].cross(v[(i + 1) % n]);
  return s;
}

// The point where edge (in, out) crosses h's plane, always computed from the inside vertex to the
// outside one: two faces sharing the edge get the same bits, so the cut's vertices match exactly.
Vec3 crossing(const Vec3& in, double d_in, const Vec3& out, double d_out) {
  return in + (out - in) * (d_in / (d_in - d_out));
}

}  // namespace

double polygon_area(const Polygon& v) {
  if (v.size() < 3) return 0;
  Vec3 twice = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < v.size(); ++k) twice += (v[k] - v[0]).cross(v[k + 1] - v[0]);
  return 0.5 * twice.norm();
}

Polygon clip_polygon(const Polygon& poly, const HalfSpace& h, double tol) {
  // Each vertex is in (d > tol), on (|d| <= tol) or out (d < -tol). Kept: in and on vertices, and
  // the crossing of every edge from an in vertex to an out vertex or back. An on vertex is itself
  // the crossing, so the result has no near-duplicate vertices.
  const std::size_t n = poly.size();
  std::vector<double> d(n);
  bool any_out = false;
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = h.distance(poly[i]);
    any_out = any_out || d[i] < -tol;
  }
  if (!any_out) return poly;
  Polygon out;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (d[i] >= -tol) out.push_back(poly[i]);
    if (d[i] > tol && d[j] < -tol) out.push_back(crossing(poly[i], d[i], poly[j], d[j]));
    if (d[i] < -tol && d[j] > tol) out.push_back(crossing(poly[j], d[j], poly[i], d[i]));
  }
  if (out.size() < 3) out.clear();
  return out;
}

Polygon clip_polygon_to(const Polygon& poly, const Polygon& window) {
  const std::size_t n = window.size();
  if (n < 3) return {};
  const Vec3 normal = newell_normal(window, n).normalized();
  Vec3 centre = Vec3::Zero();
  for (const Vec3& w : window) centre += w;
  centre /= static_cast<double>(n);
  double size = 0;
  for (const Vec3& w : window) size = std::max(size, (w - centre).norm());
  Polygon out = poly;
  for (std::size_t i = 0; i < n && !out.empty(); ++i) {
    // The plane through edge i, normal to the window, facing the window's inside.
    Vec3 m = normal.cross(window[(i + 1) % n] - window[i]).normalized();
    if (m.dot(centre - window[i]) < 0) m = -m;
    out = clip_polygon(out, HalfSpace::through(window[i], m), 1e-9 * size);
  }
  return out;
}

ConvexPolytope::ConvexPolytope(const Vec3& lo, const Vec3& hi) : tol_(1e-9 * (hi - lo).norm()) {
  const Vec3 mid = 0.5 * (lo + hi);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Polygon f = box_face(lo, hi, axis, side == 1);
      // Counter-clockwise seen from outside: the normal points away from the box's centre.
      if (newell_normal(f, f.size()).dot(f[0] - mid) < 0) std::reverse(f.begin(), f.end());
      faces_.push_back(f);
    }
}

void ConvexPolytope::clip(const HalfSpace& h) {
  if (faces_.empty()) return;
  bool any_in = false, any_out = false;
  for (const Polygon& f : faces_)
    for (const Vec3& v : f) {
      const double d = h.distance(v);
      any_in = any_in || d > tol_;
      any_out = any_out || d < -tol_;
    }
  if (!any_out) return;  // wholly inside (a plane through a face included): nothing to cut
  if (!any_in) {         // wholly outside, or only touching the plane: nothing is left
    faces_.clear();
    return;
  }
  // Clip every face; the clipped faces' vertices on the plane outline the new face.
  std::vector<Polygon> kept;
  Polygon cap;
  for (const Polygon& f : faces_) {
    Polygon c = clip_polygon(f, h, tol_);
    for (const Vec3& v : c)
      if (std::abs(h.distance(v)) <= tol_) cap.push_back(v);
    if (c.size() >= 3) kept.push_back(std::move(c));
  }
  // Order the cap's points by angle about their mean, counter-clockwise seen from outside (the
  // outward normal is -h.normal), dropping repeats (each point comes from two faces).
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : cap) mean += v;
  mean /= static_cast<double>(std::max<std::size_t>(1, cap.size()));
  const Vec3 w = -h.normal;
  const Vec3 u = (std::abs(w[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(w).normalized();
  const Vec3 v = w.cross(u);
  auto angle = [&](const Vec3& p) { return std::atan2((p - mean).dot(v), (p - mean).dot(u)); };
  std::sort(cap.begin(), cap.end(), [&](const Vec3& a, const Vec3& b) { return angle(a) < angle(b); });
  Polygon face;
  for (const Vec3& p : cap)
    if (face.empty() || (p - face.back()).norm() > tol_) face.push_back(p);
  while (face.size() > 1 && (face.front() - face.back()).norm() <= tol_) face.pop_back();
  if (face.size() >= 3) kept.push_back(std::move(face));
  faces_ = std::move(kept);
}

double ConvexPolytope::volume() const {
  // Divergence theorem over fan triangles, about a vertex of the polytope (smaller round-off than
  // about the origin): V = 1/6 Σ (a − c)·((b − c) × (d − c)) for each triangle (a, b, d).
  if (faces_.empty()) return 0;
  const Vec3 c = faces_[0][0];
  double six = 0;
  for (const Polygon& f : faces_)
    for (std::size_t k = 1; k + 1 < f.size(); ++k) six += (f[0] - c).dot((f[k] - c).cross(f[k + 1] - c));
  return six / 6;
}

Polygon ConvexPolytope::face_in(const HalfSpace& h) const {
  for (const Polygon& f : faces_) {
    bool on = true;
    for (const Vec3& v : f) on = on && std::abs(h.distance(v)) <= tol_;
    if (on) return f;
  }
  return {};
}

Container::Container(const std::vector<Wall>& walls, double t, const Particles& p, const Vec3& gravity)
    : walls_(walls), t_(t), particles_(p), bounds_(walls.size(), -1), planes_(walls.size()), have_plane_(walls.size(), 0) {
  // One pass over the centres, in parallel (a servo builds a container every step): chunks of a
  // fixed size, their sums added in chunk order, so the centroid has the same bits for any thread
  // count (below one chunk, those of the plain sum); the box and the top are exact in any order.
  const bool up = gravity.norm() > 0;
  const Vec3 down = up ? Vec3(gravity.normalized()) : Vec3::Zero();
  constexpr long kChunk = 4096;
  const long n = static_cast<long>(p.size()), chunks = (n + kChunk - 1) / kChunk;
  struct Part {
    Vec3 sum = Vec3::Zero(), lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    double top = -INFINITY;
  };
  std::vector<Part> parts(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (long c = 0; c < chunks; ++c) {
    Part q;  // in registers: a chunk's entry of `parts`, which the compiler must assume p.x may alias, is written once
    const long first = c * kChunk, last = std::min(n, first + kChunk);
    for (long i = first; i < last; ++i) {
      q.sum += p.x[i], q.lo = q.lo.cwiseMin(p.x[i]), q.hi = q.hi.cwiseMax(p.x[i]);
      if (up) q.top = std::max(q.top, -down.dot(p.x[i]) + p.radius[i]);
    }
    parts[c] = q;
  }
  double top = -INFINITY;
  for (const Part& q : parts) centroid_ += q.sum, lo_ = lo_.cwiseMin(q.lo), hi_ = hi_.cwiseMax(q.hi), top = std::max(top, q.top);
  if (n > 0) centroid_ /= static_cast<double>(n);
  if (up && n > 0) {
    top_ = HalfSpace{down, -top};  // keep {x : up·x <= top}, up = -g/|g|: normal g/|g|, offset -top
    has_top_ = true;
  }
}

Polygon Container::vertices(std::size_t k) const { return walls_[k].vertices_at(t_); }

const HalfSpace& Container::plane(std::size_t k) {
  if (!have_plane_[k]) {
    const Polygon v = vertices(k);
    Vec3 n = newell_normal(v, v.size()).normalized();
    if (n.dot(centroid_ - v[0]) < 0) n = -n;  // facing the particles
    planes_[k] = HalfSpace::through(v[0], n);
    have_plane_[k] = 1;
  }
  return planes_[k];
}

bool Container::bounds(std::size_t k) {
  if (bounds_[k] < 0) {
    const HalfSpace& h = plane(k);
    bounds_[k] = 1;
    // The distance is affine, so over the centres' box it is least at a corner: a margin above the
    // rounding at every corner answers for every centre without a pass over them (a servo asks
    // every step).
    const double margin = 1e-12 * (std::abs(h.offset) + std::max(lo_.cwiseAbs().maxCoeff(), hi_.cwiseAbs().maxCoeff()));
    bool corners_inside = particles_.size() > 0;
    for (int c = 0; c < 8 && corners_inside; ++c) {
      const Vec3 corner((c & 1) ? hi_.x() : lo_.x(), (c & 2) ? hi_.y() : lo_.y(), (c & 4) ? hi_.z() : lo_.z());
      corners_inside = h.distance(corner) > margin;
    }
    if (corners_inside) return true;
    for (const Vec3& x : particles_.x)
      if (h.distance(x) < 0) {
        bounds_[k] = 0;
        break;
      }
  }
  return bounds_[k] == 1;
}

double Container::volume() {
  if (walls_.empty() || particles_.size() == 0) return 0;
  // A box holding every wall vertex and every sphere (so that a container open on one side, e.g. a
  // floor alone, is still closed by the spheres' extent), cut by the planes.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Wall& w : walls_)
    for (const Vec3& v : w.vertices_at(t_)) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    lo = lo.cwiseMin(particles_.x[i] - Vec3::Constant(particles_.radius[i]));
    hi = hi.cwiseMax(particles_.x[i] + Vec3::Constant(particles_.radius[i]));
  }
  ConvexPolytope shape(lo, hi);
  for (std::size_t k = 0; k < walls_.size(); ++k)
    if (bounds(k)) shape.clip(plane(k));
  if (has_top_) shape.clip(top_);
  return shape.volume();
}

double Container::wall_area(std::size_t k) {
  const Polygon own = vertices(k);
  double size = 0;
  for (const Vec3& v : own) size = std::max(size, (v - own[0]).norm());
  const double tol = 1e-9 * size;
  Polygon inside = own;
  for (std::size_t j = 0; j < walls_.size() && inside.size() >= 3; ++j) {
    if (j == k) continue;
    const HalfSpace& h = plane(j);
    // Only a plane that cuts the polygon matters; whether it bounds the particles costs a pass over
    // them, so ask only then.
    bool cuts = false;
    for (const Vec3& v : inside) cuts = cuts || h.distance(v) < -tol;
    if (cuts && bounds(j)) inside = clip_polygon(inside, h, tol);
  }
  if (inside.size() < 3) return polygon_area(own);  // beyond the other walls: its own area
  if (has_top_) {
    const double below = polygon_area(clip_polygon(inside, top_, tol));
    if (below > 0) return below;
  }
  return polygon_area(inside);
}

}  // namespace dem
