#include "sim/force_loop.hpp"

#include <cmath>

#include "contact/contact_law.hpp"
#include "sim/simulation.hpp"

namespace dem {

namespace {

// Each contact is written by one thread only; no atomics (DESIGN.md).
// Each loop also returns the largest overlap relative to the smaller radius (a stability check).
template <class Normal>
double pair_forces(const ForceLoopInput& in, ContactList& pc) {
  const Particles& p = in.particles;
  const long n = static_cast<long>(pc.size());
  double worst = 0;
#pragma omp parallel for schedule(static) reduction(max : worst)
  for (long k = 0; k < n; ++k) {
    const int i = pc.slot_i[k], j = pc.slot_j[k];
    const Vec3 d = p.x[j] - p.x[i];
    const double r = p.radius[i] + p.radius[j];
    const double d2 = d.squaredNorm();
    if (d2 >= r * r && !pc.bonded[k]) {  // a candidate, not a contact: no force, no history
      pc.active[k] = 0;
      pc.spring[k] = Vec3::Zero();
      continue;
    }
    const double dist = std::sqrt(d2);
    ContactKinematics c;
    c.n = d / dist;
    c.overlap = r - dist;  // eq. 2.11
    c.v_rel = p.v[j] - p.v[i];
    c.w_arm = p.radius[j] * p.w[j] + p.radius[i] * p.w[i];
    c.m_eff = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
    const ContactForce f =
        ContactLaw<Normal>::evaluate(in.materials.pair(p.material[i], p.material[j]), c, in.dt, pc.spring[k], pc.bonded[k]);
    pc.active[k] = 1;
    pc.normal[k] = c.n;
    pc.force[k] = f.on_i;
    pc.tangential[k] = f.tangential;
    worst = std::max(worst, c.overlap / std::min(p.radius[i], p.radius[j]));
  }
  return worst;
}

template <class Normal>
double wall_forces(const ForceLoopInput& in, ContactList& wc) {
  const Particles& p = in.particles;
  const long n = static_cast<long>(wc.size());
  double worst = 0;
#pragma omp parallel for schedule(static) reduction(max : worst)
  for (long k = 0; k < n; ++k) {
    const int i = wc.slot_i[k], w = wc.slot_j[k];
    const WallGeometry& g = in.geometry[w];
    const Vec3 cp = closest_point(g, p.x[i]);
    const Vec3 d = cp - p.x[i];
    const double d2 = d.squaredNorm();
    if (d2 >= p.radius[i] * p.radius[i] && !wc.bonded[k]) {
      wc.active[k] = 0;
      wc.spring[k] = Vec3::Zero();
      continue;
    }
    const double dist = std::sqrt(d2);
    ContactKinematics c;
    // A centre exactly on the wall has no direction to the contact point: use the plane normal.
    c.n = dist > 0 ? Vec3(d / dist) : g.normal;
    c.overlap = p.radius[i] - dist;  // eq. 2.17
    c.v_rel = g.velocity - p.v[i];   // eq. 2.18: the wall's velocity enters
    c.w_arm = p.radius[i] * p.w[i];
    c.m_eff = p.mass[i];
    const ContactForce f =
        ContactLaw<Normal>::evaluate(in.materials.pair(p.material[i], in.walls[w].material), c, in.dt, wc.spring[k], wc.bonded[k]);
    wc.active[k] = 1;
    wc.normal[k] = c.n;
    wc.force[k] = f.on_i;
    wc.tangential[k] = f.tangential;
    worst = std::max(worst, c.overlap / p.radius[i]);
  }
  return worst;
}

template <class Normal>
double all_forces(const ForceLoopInput& in, ContactList& pairs, ContactList& walls) {
  return std::max(pair_forces<Normal>(in, pairs), wall_forces<Normal>(in, walls));
}

}  // namespace

ForceVariant choose_force_variant(const Simulation& sim) {
  if (!sim.has_bonds()) return ForceVariant::Cundall;
  const std::optional<NormalLaw> law = sim.materials.common_law();
  if (!law) return ForceVariant::Mixed;
  switch (*law) {
    case NormalLaw::Cundall: return ForceVariant::Cundall;
    case NormalLaw::Liu: return ForceVariant::Liu;
    case NormalLaw::Mendes: return ForceVariant::Mendes;
  }
  return ForceVariant::Mixed;
}

const char* variant_name(ForceVariant v) {
  switch (v) {
    case ForceVariant::Cundall: return "cundall";
    case ForceVariant::Liu: return "liu";
    case ForceVariant::Mendes: return "mendes";
    case ForceVariant::Mixed: return "mixed";
  }
  return "?";
}

double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls) {
  switch (variant) {
    case ForceVariant::Cundall: return all_forces<CundallNormal>(in, pairs, walls);
    case ForceVariant::Liu: return all_forces<LiuNormal>(in, pairs, walls);
    case ForceVariant::Mendes: return all_forces<MendesNormal>(in, pairs, walls);
    case ForceVariant::Mixed: return all_forces<MixedNormal>(in, pairs, walls);
  }
  return 0;
}

}  // namespace dem
