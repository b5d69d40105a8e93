#include "generation/insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include "generation/sphere_grid.hpp"
#include "walls/wall.hpp"

namespace dem {

namespace {

// SplitMix64's finaliser: consecutive indices give unrelated seeds.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
std::uint64_t mix(std::uint64_t a, std::uint64_t b) { return mix(mix(a) ^ b); }

// The particles present and those placed in this event (a SphereGrid of cells one largest
// diameter wide); periodic axes by testing the candidate's images.
class Occupancy {
 public:
  Occupancy(const Particles& p, const PeriodicBox& box, double r_new_max)
      : box_(box), r_max_(largest_radius(p, r_new_max)), grid_(p, 2 * r_max_) {
    for (std::size_t k = 0; k < p.size(); ++k) add(static_cast<int>(k));
  }
  void add(int slot) { grid_.add(slot); }
  bool free(const Vec3& x, double a) const {
    // The images of x that may reach a particle across a periodic boundary.
    Vec3 images[27];
    int n = 1;
    images[0] = x;
    const double reach = a + r_max_;
    for (int d = 0; d < 3; ++d) {
      if (!box_.axis[d]) continue;
      const int m = n;
      for (int s : {-1, 1}) {
        if ((s > 0 && x[d] - box_.lo[d] >= reach) || (s < 0 && box_.hi[d] - x[d] >= reach)) continue;
        for (int k = 0; k < m; ++k) images[n] = images[k], images[n][d] += s * box_.length(d), ++n;
      }
    }
    for (int k = 0; k < n; ++k)
      if (!grid_.free_at(images[k], a)) return false;
    return true;
  }

 private:
  static double largest_radius(const Particles& p, double r) {
    for (double a : p.radius) r = std::max(r, a);
    return r;
  }

  const PeriodicBox& box_;
  double r_max_;
  SphereGrid grid_;
};

// The wall elements near a region now (their bounding boxes within r_max of the region's).
std::vector<WallGeometry> walls_near(const Simulation& sim, const Vec3& lo, const Vec3& hi, double r_max) {
  std::vector<WallGeometry> near;
  for (const Wall& w : sim.walls) {
    WallGeometry g;
    place_wall(w, sim.time, sim.dt, g);
    Vec3 a = g.vertices[0], b = g.vertices[0];
    for (int k = 1; k < g.count; ++k) a = a.cwiseMin(g.vertices[k]), b = b.cwiseMax(g.vertices[k]);
    if (((a.array() - r_max) <= hi.array()).all() && ((b.array() + r_max) >= lo.array()).all()) near.push_back(g);
  }
  return near;
}

bool clear_of_walls(const std::vector<WallGeometry>& walls, const Vec3& x, double a) {
  for (const WallGeometry& g : walls)
    if ((closest_point(g, x) - x).squaredNorm() < a * a) return false;
  return true;
}

}  // namespace

bool region_bounds(const Region& r, Vec3& lo, Vec3& hi) {
  switch (r.kind) {
    case Region::Kind::Box: lo = r.min, hi = r.max; return true;
    case Region::Kind::Sphere: lo = r.centre.array() - r.radius, hi = r.centre.array() + r.radius; return true;
    case Region::Kind::Cylinder: {
      if (!(r.length > 0)) return false;
      // Per axis: half the length along the axis's component plus the radius across it.
      for (int d = 0; d < 3; ++d) {
        const double e = 0.5 * r.length * std::abs(r.axis[d]) + r.radius * std::sqrt(std::max(0.0, 1 - r.axis[d] * r.axis[d]));
        lo[d] = r.centre[d] - e, hi[d] = r.centre[d] + e;
      }
      return true;
    }
    case Region::Kind::Mesh: r.mesh->bounds(lo, hi); return true;
    case Region::Kind::HalfSpace: return false;
  }
  return false;
}

bool sphere_in_region(const Region& r, const Vec3& x, double a) {
  switch (r.kind) {
    case Region::Kind::Box: return ((x.array() - a) >= r.min.array()).all() && ((x.array() + a) <= r.max.array()).all();
    case Region::Kind::Sphere: return a <= r.radius && (x - r.centre).norm() <= r.radius - a;
    case Region::Kind::Cylinder: {
      const Vec3 d = x - r.centre;
      const double along = d.dot(r.axis);
      if (r.length > 0 && std::abs(along) > 0.5 * r.length - a) return false;
      return a <= r.radius && (d - along * r.axis).norm() <= r.radius - a;
    }
    default: return r.contains(x);
  }
}

InsertGroup::InsertGroup(const InsertSpec& spec, const MaterialTable& materials, std::int64_t count, std::int64_t deferred)
    : spec_(spec), sizes_(spec.size, spec.radius_min, spec.radius_max), deferred_(deferred) {
  for (const Material& m : materials.materials()) density_.push_back(m.density);
  // The amount placed so far, summed again in index order: the bits of the uninterrupted run.
  for (std::int64_t i = 0; i < count; ++i) placed(draw(i));
}

InsertGroup::Draw InsertGroup::draw(std::int64_t i) const {
  std::mt19937_64 rng(mix(spec_.seed, static_cast<std::uint64_t>(i)));
  Draw d;
  d.radius = sizes_.draw(rng);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double pick = unit(rng);
  d.material = spec_.material_fractions.back().first;
  for (const auto& [m, f] : spec_.material_fractions) {
    if (pick < f) {
      d.material = m;
      break;
    }
    pick -= f;
  }
  d.mass = sphere_mass(density_[d.material], d.radius);
  return d;
}

bool InsertGroup::due(std::int64_t i, double stage_time) const {
  if (i != count_ || stage_time < spec_.start) return false;  // only the next particle's amount is known
  if (!(amount_ < spec_.total)) return false;
  return amount_ <= spec_.rate * (std::min(stage_time, spec_.end) - spec_.start);
}

void InsertGroup::placed(const Draw& d) {
  ++count_;
  amount_ += amount_of(d);
}

std::size_t insert_due(Simulation& sim, std::vector<InsertGroup>& groups, std::int64_t stage_step, double stage_time) {
  Particles& p = sim.particles;
  std::size_t inserted = 0;
  std::unique_ptr<Occupancy> space;  // built once something is due: an event with nothing due costs nothing
  for (InsertGroup& g : groups) {
    const InsertSpec& s = g.spec();
    if (stage_step % s.every != 0 || !g.due(g.count(), stage_time)) continue;
    double r_new = 0;
    for (const InsertGroup& h : groups) r_new = std::max(r_new, h.spec().radius_max);
    if (!space) space = std::make_unique<Occupancy>(p, sim.periodic, r_new);
    Vec3 lo, hi;
    region_bounds(s.region, lo, hi);
    const std::vector<WallGeometry> walls = walls_near(sim, lo, hi, s.radius_max);
    while (g.due(g.count(), stage_time)) {
      const InsertGroup::Draw d = g.draw(g.count());
      // Positions from (seed, index, step): a deferred particle tries new ones at its next event.
      std::mt19937_64 rng(mix(mix(s.seed, static_cast<std::uint64_t>(g.count())), static_cast<std::uint64_t>(sim.step)));
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      bool found = false;
      Vec3 x;
      for (int attempt = 0; attempt < s.attempts && !found; ++attempt) {
        bool inside = false;
        for (int k = 0; k < 64 && !inside; ++k) {  // a point of the region (rejection in its bounding box)
          for (int c = 0; c < 3; ++c) x[c] = lo[c] + (hi[c] - lo[c]) * unit(rng);
          inside = sphere_in_region(s.region, x, d.radius);
        }
        found = inside && clear_of_walls(walls, x, d.radius) && space->free(x, d.radius);
      }
      if (!found) {
        g.missed();  // the region is full near the draws: this particle and those after it wait
        break;
      }
      p.add(p.max_id() + 1, x, d.radius, sim.materials.materials()[d.material].density, d.material);
      p.v.back() = s.velocity;
      space->add(static_cast<int>(p.size() - 1));
      g.placed(d);
      ++inserted;
    }
  }
  // New particles: the neighbour list is built again, the contact history carried over by key.
  if (inserted) {
    sim.set_contacts(sim.pair_contacts(), sim.wall_contacts());
    sim.release_contact_views();  // the compacted copies were taken: do not carry them to the next event
  }
  return inserted;
}

std::string insert_report(const std::vector<InsertGroup>& groups, double stage_time) {
  std::ostringstream m;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const InsertGroup& g = groups[k];
    // Those due by now and not inserted: counted by drawing on from the next one.
    std::int64_t waiting = 0;
    {
      InsertGroup probe = g;
      while (waiting < 1000000 && probe.due(probe.count(), stage_time)) probe.placed(probe.draw(probe.count())), ++waiting;
    }
    m << (k ? "\n" : "") << "insert[" << k << "]: " << g.count() << " particles";
    if (g.spec().rate_kind == InsertSpec::Rate::Mass) m << ", " << g.placed_amount() << " kg";
    m << "; " << g.deferred() << " deferred at an event (no room); " << waiting << " due and not inserted at the end";
  }
  return m.str();
}

}  // namespace dem
