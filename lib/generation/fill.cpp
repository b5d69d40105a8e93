#include "generation/fill.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/error.hpp"

namespace dem {

void fill_random(Simulation& sim, const GenerationSpec& spec, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double cell = 2 * spec.radius_max;
  // Hash grid of placed spheres for O(1) overlap checks.
  std::unordered_map<long, std::vector<int>> grid;
  auto key = [&](long i, long j, long k) { return (i * 73856093L) ^ (j * 19349663L) ^ (k * 83492791L); };
  Particles& p = sim.particles;
  const Index first_id = p.max_id() + 1;
  // Given spheres first (ids in file order); they may be larger than radius_max, so the random ones
  // are checked against them directly rather than through the grid.
  const std::size_t first = p.size();
  for (const PlacedSphere& s : spec.placed) {
    p.add(first_id + static_cast<Index>(p.size() - first), s.centre, s.radius, sim.materials.materials()[s.material].density,
          s.material);
  }
  auto clear_of_placed = [&](const Vec3& x, double a) {
    for (std::size_t k = 0; k < spec.placed.size(); ++k)
      if ((p.x[first + k] - x).norm() < a + p.radius[first + k]) return false;
    return true;
  };
  const std::size_t total = first + spec.placed.size() + static_cast<std::size_t>(spec.count);
  const long max_attempts = 1000L * spec.count + 100000;
  long attempts = 0;
  while (p.size() < total) {
    if (++attempts > max_attempts) {
      std::ostringstream m;
      m << "generation: placed only " << p.size() - first - spec.placed.size() << " of " << spec.count << " random spheres in the box after " << max_attempts
        << " attempts; enlarge generation.box_min/box_max or lower generation.count (random placement reaches a solid "
           "fraction of about 0.3; settling compacts it)";
      throw InputError(m.str());
    }
    const double a = spec.radius_min + (spec.radius_max - spec.radius_min) * unit(rng);
    Vec3 x;
    for (int d = 0; d < 3; ++d) x[d] = spec.box_min[d] + a + (spec.box_max[d] - spec.box_min[d] - 2 * a) * unit(rng);
    double pick = unit(rng);
    int mat = spec.material_fractions.back().first;
    for (const auto& [m, f] : spec.material_fractions) {
      if (pick < f) {
        mat = m;
        break;
      }
      pick -= f;
    }
    const long ci = static_cast<long>(std::floor(x[0] / cell)), cj = static_cast<long>(std::floor(x[1] / cell)),
               ck = static_cast<long>(std::floor(x[2] / cell));
    bool free = clear_of_placed(x, a);
    for (long di = -1; di <= 1 && free; ++di)
      for (long dj = -1; dj <= 1 && free; ++dj)
        for (long dk = -1; dk <= 1 && free; ++dk) {
          auto it = grid.find(key(ci + di, cj + dj, ck + dk));
          if (it == grid.end()) continue;
          for (int o : it->second) {
            const double r = a + p.radius[o];
            if ((p.x[o] - x).squaredNorm() < r * r) {
              free = false;
              break;
            }
          }
        }
    if (!free) continue;
    grid[key(ci, cj, ck)].push_back(static_cast<int>(p.size()));
    p.add(first_id + static_cast<Index>(p.size() - first), x, a, sim.materials.materials()[mat].density, mat);
  }
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

namespace {
// Which particles have their centre inside `region`, one byte each. The tests are independent (a
// mesh region's cost a particle each): in parallel.
std::vector<char> centres_inside(const Particles& p, const Region& region) {
  std::vector<char> in(p.size());
  const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < n; ++k) in[k] = region.contains(p.x[k]);
  return in;
}
}  // namespace

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
  Particles& p = sim.particles;
  const std::vector<char> in = centres_inside(p, region);
  std::vector<bool> keep(p.size());
  std::set<Index> gone;
  for (std::size_t k = 0; k < p.size(); ++k) {
    keep[k] = (in[k] != 0) != inside;
    if (!keep[k]) gone.insert(p.id[k]);
  }
  if (gone.empty()) return 0;
  p.keep_only(keep);
  // The contacts of the removed particles go too, so that a checkpoint written now names only
  // particles it holds (a run would drop them at its next neighbour search anyway).
  ContactList pairs, walls;
  const ContactList& pc = sim.pair_contacts();
  for (std::size_t k = 0; k < pc.size(); ++k)
    if (!gone.count(pc.key_i[k]) && !gone.count(pc.key_j[k])) pairs.push_back_from(pc, k);
  const ContactList& wc = sim.wall_contacts();
  for (std::size_t k = 0; k < wc.size(); ++k)
    if (!gone.count(wc.key_i[k])) walls.push_back_from(wc, k);
  sim.set_contacts(std::move(pairs), std::move(walls));
  return gone.size();
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
