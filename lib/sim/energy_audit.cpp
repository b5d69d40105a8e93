#include "sim/energy_audit.hpp"

#include <algorithm>
#include <cmath>

#include "contact/kinematics.hpp"
#include "contact/model_table.hpp"
#include "forces/force_loop.hpp"

namespace dem {

MechanicalEnergy mechanical_energy(const Particles& p, const Vec3& gravity, const PeriodicBox& box,
                                   const std::vector<std::size_t>* order, long block) {
  // Runs small enough that two threads share 10^4 particles evenly (runs of 4,096: one thread
  // summed two of the three, and the check took as long as on one thread).
  const long n = static_cast<long>(p.size());
  const long runs = (n + block - 1) / block;
  std::vector<MechanicalEnergy> part(runs);
#pragma omp parallel for schedule(static)
  for (long b = 0; b < runs; ++b) {
    for (long q = b * block; q < std::min(n, (b + 1) * block); ++q)
      add_energy_of(p, gravity, box, order ? (*order)[q] : static_cast<std::size_t>(q), part[b]);  // as energy_of_slots without order
  }
  return sum_in_order(part);
}

namespace {

// Normal part of the bound for overlap u (> 0 compression) of a pair with constants q: its law's.
double normal_energy_bound(const PairParams& q, double u, double r_eff, bool bonded) {
  return with_normal_law(q.law, [&](auto law) { return law.stored_energy(q, u, r_eff, bonded); });
}

double spring_energy(const PairParams& q, const Vec3& spring, double u, double r_eff) {
  return with_tangential_law(q, [&](auto law) { return law.stored_energy(q, spring, u, r_eff); });
}

}  // namespace

double stored_energy_bound(const Particles& p, const MaterialTable& materials, const std::vector<Wall>& walls,
                           const std::vector<WallGeometry>& geometry, const PeriodicBox& box, const ContactList& pairs,
                           const ContactList& wall_contacts) {
  double e = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!pairs.active[k]) continue;
    const int i = pairs.slot_i[k], j = pairs.slot_j[k];
    const PairParams& q = materials.pair(p.material[i], p.material[j]);
    const double u = p.radius[i] + p.radius[j] - separation(p, box, i, j).norm();
    const double r_eff = effective_radius(p.radius[i], p.radius[j]);
    e += normal_energy_bound(q, u, r_eff, pairs.bonded[k]) + spring_energy(q, pairs.spring[k], u, r_eff);
  }
  for (std::size_t k = 0; k < wall_contacts.size(); ++k) {
    if (!wall_contacts.active[k]) continue;
    const int i = wall_contacts.slot_i[k], w = wall_contacts.slot_j[k];
    const PairParams& q = materials.pair(p.material[i], walls[w].material);
    const double u = p.radius[i] - (closest_point(geometry[w], p.x[i]) - p.x[i]).norm();
    e += normal_energy_bound(q, u, p.radius[i], wall_contacts.bonded[k]) + spring_energy(q, wall_contacts.spring[k], u, p.radius[i]);
  }
  return e;
}

double prescribed_power(const Particles& p, const LoadSum* force, const LoadSum* torque) {
  double power = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.fixed[k] == kPrescribed) power -= force[k].v.dot(p.v[k]) + torque[k].v.dot(p.w[k]);
  return power;
}

double EnergyBalance::scale() const {
  return std::max(0.0, start.kinetic) + stored0 + wall_work_abs + std::abs(now.potential - start.potential) + potential_scale;
}

}  // namespace dem
