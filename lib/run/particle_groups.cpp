#include "run/particle_groups.hpp"

#include <sstream>

namespace dem {

std::vector<std::size_t> select_group(const Simulation& sim, const ParticleGroupSpec& group) {
  const Particles& p = sim.particles;
  std::vector<std::size_t> slots;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (group.material >= 0 && p.material[k] != group.material) continue;
    if (group.by_ids && (p.id[k] < group.id_first || p.id[k] > group.id_last)) continue;
    if (group.region && group.region->contains(p.x[k]) != group.inside) continue;
    slots.push_back(k);
  }
  return slots;
}

std::size_t set_group_velocity(Simulation& sim, const VelocitySpec& spec) {
  Particles& p = sim.particles;
  std::size_t n = 0;
  for (std::size_t k : select_group(sim, spec.group)) {
    ++n;
    if (p.fixed[k] == kHeld) continue;
    p.v[k] = spec.velocity;
    if (spec.angular_velocity) p.w[k] = *spec.angular_velocity;
  }
  return n;
}

std::size_t start_prescribed(Simulation& sim, const VelocitySpec& spec) {
  Particles& p = sim.particles;
  const std::vector<std::size_t> slots = select_group(sim, spec.group);
  for (std::size_t k : slots) {
    p.fixed[k] = kPrescribed;
    p.v[k] = spec.velocity;
    p.w[k] = spec.angular_velocity.value_or(Vec3::Zero());
  }
  return slots.size();
}

std::size_t end_prescribed(Simulation& sim) {
  Particles& p = sim.particles;
  std::size_t n = 0;
  for (std::uint8_t& f : p.fixed)
    if (f == kPrescribed) f = kFree, ++n;
  return n;
}

Vec3 force_on_prescribed(const Simulation& sim) {
  const Particles& p = sim.particles;
  Vec3 sum = Vec3::Zero();
  for (std::size_t k : p.slots_by_id())  // in id order: the same bits for any storage order
    if (p.fixed[k] == kPrescribed) sum += sim.net_force(k) - p.mass[k] * sim.params.gravity;
  return sum;
}

std::string describe_group(const Simulation& sim, const ParticleGroupSpec& group) {
  std::ostringstream s;
  const char* sep = "";
  if (group.material >= 0) s << sep << "material \"" << sim.materials.materials()[group.material].name << "\"", sep = ", ";
  if (group.by_ids) s << sep << "ids " << group.id_first << " to " << group.id_last, sep = ", ";
  if (group.region) s << sep << (group.inside ? "inside" : "outside") << " the region";
  return s.str();
}

}  // namespace dem
