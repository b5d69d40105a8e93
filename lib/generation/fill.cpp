#include "generation/fill.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "generation/size_distribution.hpp"
#include "generation/sphere_grid.hpp"

namespace dem {

namespace {

// The spheres placed so far (a SphereGrid of cells 2 radius_max wide); the given spheres may be
// larger than radius_max, so candidates are checked against them directly.
class FreeSpace {
 public:
  FreeSpace(const Particles& p, const GenerationSpec& spec, std::size_t first)
      : p_(p), spec_(spec), first_(first), grid_(p, 2 * spec.radius_max) {}

  bool free(const Vec3& x, double a) const {
    for (std::size_t k = 0; k < spec_.placed.size(); ++k)
      if ((p_.x[first_ + k] - x).norm() < a + p_.radius[first_ + k]) return false;
    return grid_.free_at(x, a);
  }
  void add(int slot) { grid_.add(slot); }

 private:
  const Particles& p_;
  const GenerationSpec& spec_;
  std::size_t first_;
  SphereGrid grid_;
};

Vec3 draw_centre(const GenerationSpec& spec, double a, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vec3 x;
  for (int d = 0; d < 3; ++d) x[d] = spec.box_min[d] + a + (spec.box_max[d] - spec.box_min[d] - 2 * a) * unit(rng);
  return x;
}

int draw_material(const GenerationSpec& spec, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double pick = unit(rng);
  for (const auto& [m, f] : spec.material_fractions) {
    if (pick < f) return m;
    pick -= f;
  }
  return spec.material_fractions.back().first;
}

[[noreturn]] void too_full(const GenerationSpec& spec, std::size_t placed, long max_attempts) {
  std::ostringstream m;
  m << "generation: placed only " << placed << " of " << spec.count << " random spheres in the box after " << max_attempts
    << " attempts; enlarge generation.box_min/box_max or lower generation.count (random placement reaches a solid "
       "fraction of about 0.3; settling compacts it)";
  throw InputError(m.str());
}

long max_attempts(const GenerationSpec& spec) { return 1000L * spec.count + 100000; }

// No [generation.size] (uniform radii by default): radius, centre and material drawn afresh at every
// attempt, exactly as before size distributions existed, so older scenes give the same bits. A
// crowded box rejects large candidates more often, so the radii come out smaller than uniform.
void place_drawn_per_attempt(Simulation& sim, const GenerationSpec& spec, const RadiusSampler& sizes, FreeSpace& space,
                             Index first_id, std::size_t first, std::mt19937_64& rng) {
  Particles& p = sim.particles;
  const std::size_t total = first + spec.placed.size() + static_cast<std::size_t>(spec.count);
  long attempts = 0;
  while (p.size() < total) {
    if (++attempts > max_attempts(spec)) too_full(spec, p.size() - first - spec.placed.size(), max_attempts(spec));
    const double a = sizes.draw(rng);
    const Vec3 x = draw_centre(spec, a, rng);
    const int mat = draw_material(spec, rng);
    if (!space.free(x, a)) continue;
    p.add(first_id + static_cast<Index>(p.size() - first), x, a, sim.materials.materials()[mat].density, mat);
    space.add(static_cast<int>(p.size() - 1));
  }
}

// A [generation.size] table, uniform included: all radii drawn first (so the set drawn is the
// distribution asked: a rejected candidate keeps its radius), then placed largest first (large
// spheres find room while the box is empty); each sphere's material is drawn once, its centre at
// every attempt.
void place_largest_first(Simulation& sim, const GenerationSpec& spec, const RadiusSampler& sizes, FreeSpace& space,
                         Index first_id, std::size_t first, std::mt19937_64& rng) {
  Particles& p = sim.particles;
  std::vector<double> radii = sizes.draw(static_cast<std::size_t>(spec.count), rng);
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  long attempts = 0;
  for (double a : radii) {
    const int mat = draw_material(spec, rng);
    for (;;) {
      if (++attempts > max_attempts(spec)) too_full(spec, p.size() - first - spec.placed.size(), max_attempts(spec));
      const Vec3 x = draw_centre(spec, a, rng);
      if (!space.free(x, a)) continue;
      p.add(first_id + static_cast<Index>(p.size() - first), x, a, sim.materials.materials()[mat].density, mat);
      space.add(static_cast<int>(p.size() - 1));
      break;
    }
  }
}

}  // namespace

void fill_random(Simulation& sim, const GenerationSpec& spec, std::mt19937_64& rng) {
  const RadiusSampler sizes(spec.size, spec.radius_min, spec.radius_max);
  Particles& p = sim.particles;
  const Index first_id = p.max_id() + 1;
  const std::size_t first = p.size();
  // Given spheres first (ids in file order).
  for (const PlacedSphere& s : spec.placed) {
    p.add(first_id + static_cast<Index>(p.size() - first), s.centre, s.radius, sim.materials.materials()[s.material].density,
          s.material);
  }
  FreeSpace space(p, spec, first);
  if (spec.size.kind == SizeSpec::Kind::Uniform && !spec.size.given) place_drawn_per_attempt(sim, spec, sizes, space, first_id, first, rng);
  else place_largest_first(sim, spec, sizes, space, first_id, first, rng);
}

void tile(Simulation& sim, int nx, int ny, int nz, const Vec3& period) {
  const Particles src = sim.particles;
  Particles& p = sim.particles;
  p = Particles{};
  Index next = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Vec3 shift(i * period[0], j * period[1], k * period[2]);
        for (std::size_t s = 0; s < src.size(); ++s) {
          p.id.push_back(next++);
          p.x.push_back(src.x[s] + shift);
          p.v.push_back(src.v[s]);
          p.w.push_back(src.w[s]);
          p.x_ref.push_back(src.x[s] + shift);
          p.image.push_back(Vec3i::Zero());
          p.radius.push_back(src.radius[s]);
          p.mass.push_back(src.mass[s]);
          p.material.push_back(src.material[s]);
          p.fixed.push_back(src.fixed[s]);
        }
      }
  sim.set_contacts({}, {});
}

// The tests are independent (a mesh region's cost a particle each): in parallel.
std::vector<char> centres_inside(const Particles& p, const Region& region) {
  std::vector<char> in(p.size());
  const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < n; ++k) in[k] = region.contains(p.x[k]);
  return in;
}

std::size_t set_fixed(Simulation& sim, const Region* region, bool inside, bool fixed) {
  Particles& p = sim.particles;
  const std::vector<char> in = region ? centres_inside(p, *region) : std::vector<char>(p.size(), 1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if ((in[k] != 0) != inside) continue;
    p.fixed[k] = fixed;
    if (fixed) p.v[k] = p.w[k] = Vec3::Zero();
    ++n;
  }
  return n;
}

std::size_t remove_particles(Simulation& sim, const Region& region, bool inside) {
  std::vector<char> gone = centres_inside(sim.particles, region);
  if (!inside)
    for (char& g : gone) g = !g;
  return remove_marked(sim, gone);
}

std::size_t remove_marked(Simulation& sim, const std::vector<char>& gone) {
  const std::size_t count = static_cast<std::size_t>(std::count_if(gone.begin(), gone.end(), [](char g) { return g != 0; }));
  if (count == 0) return 0;
  if (sim.remove_from_lists(gone)) return count;  // after a step: no search follows
  Particles& p = sim.particles;
  std::vector<bool> keep(p.size());
  std::set<Index> ids;
  for (std::size_t k = 0; k < p.size(); ++k) {
    keep[k] = !gone[k];
    if (gone[k]) ids.insert(p.id[k]);
  }
  if (ids.empty()) return 0;
  p.keep_only(keep);
  // The contacts of the removed particles go too, so that a checkpoint written now names only
  // particles it holds (a run would drop them at its next neighbour search anyway).
  ContactList pairs, walls;
  const ContactList& pc = sim.pair_contacts();
  for (std::size_t k = 0; k < pc.size(); ++k)
    if (!ids.count(pc.key_i[k]) && !ids.count(pc.key_j[k])) pairs.push_back_from(pc, k);
  const ContactList& wc = sim.wall_contacts();
  for (std::size_t k = 0; k < wc.size(); ++k)
    if (!ids.count(wc.key_i[k])) walls.push_back_from(wc, k);
  sim.set_contacts(std::move(pairs), std::move(walls));
  return ids.size();
}

std::pair<Vec3, Vec3> sphere_bounds(const Particles& p) {
  if (p.size() == 0) return {Vec3::Zero(), Vec3::Zero()};
  Vec3 lo = p.x[0], hi = p.x[0];
  for (std::size_t k = 0; k < p.size(); ++k) {
    lo = lo.cwiseMin(p.x[k] - Vec3::Constant(p.radius[k]));
    hi = hi.cwiseMax(p.x[k] + Vec3::Constant(p.radius[k]));
  }
  return {lo, hi};
}

}  // namespace dem
