#include "run/particle_track.hpp"

#include "core/error.hpp"

namespace dem {

namespace {
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

std::size_t find_id(const Particles& p, Index id) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == id) return i;
  return kNone;
}

// Storage indices of the ids; InputError for a missing one.
std::vector<std::size_t> locate(const std::vector<Index>& ids, const Particles& p) {
  std::vector<std::size_t> index;
  for (Index id : ids) {
    index.push_back(find_id(p, id));
    if (index.back() == kNone)
      throw InputError("--track-ids: no particle with id " + std::to_string(id) + " (the model has " + std::to_string(p.size()) +
                       " particles; removed ones are gone)");
  }
  return index;
}
}  // namespace

ParticleTrack::ParticleTrack(const std::string& path, const std::vector<Index>& ids, const Simulation& sim, std::int64_t every,
                             std::int64_t resume_step)
    : ids_(path.empty() ? std::vector<Index>{} : ids),
      index_(locate(ids_, sim.particles)),
      every_(every > 0 ? every : 1),
      csv_(path, "step,time_s,id,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s\n", "particle track", resume_step) {}

std::size_t ParticleTrack::index_of(const Particles& p, std::size_t k) {
  // Storage may be reordered between rows; the id decides.
  if (index_[k] >= p.size() || p.id[index_[k]] != ids_[k]) index_[k] = find_id(p, ids_[k]);
  return index_[k];
}

void ParticleTrack::record(const Simulation& sim, std::int64_t steps_done, bool first_or_last) {
  if (!csv_.active() || (steps_done % every_ != 0 && !first_or_last)) return;
  const Particles& p = sim.particles;
  for (std::size_t k = 0; k < ids_.size(); ++k) {
    const std::size_t i = index_of(p, k);
    std::fprintf(csv_.file(), "%lld,%.12g,%lld,%.12g,%.12g,%.12g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                 static_cast<long long>(sim.step), sim.time, static_cast<long long>(ids_[k]), p.x[i].x(), p.x[i].y(),
                 p.x[i].z(), p.v[i].x(), p.v[i].y(), p.v[i].z(), p.w[i].x(), p.w[i].y(), p.w[i].z());
  }
  csv_.flush();
}

}  // namespace dem
