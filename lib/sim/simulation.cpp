#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact/cundall.hpp"
#include "core/error.hpp"

namespace dem {

void Simulation::advance() {
  find_contacts();
  compute_forces();
  integrate();
  time += dt;
  ++step;
}

void Simulation::find_contacts() {
  found_.clear();
  cells_.find_overlaps(particles, found_);
  std::sort(found_.begin(), found_.end());
  update_contacts(pair_contacts, found_);

  found_.clear();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const std::vector<Vec3> v = walls[w].vertices_at(time);
    const Vec3 nrm = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const Vec3 c = closest_point_on_polygon(v.data(), static_cast<int>(v.size()), nrm, particles.x[k]);
      const double a = particles.radius[k];
      if ((c - particles.x[k]).squaredNorm() < a * a)
        found_.push_back({particles.id[k], static_cast<Index>(w), static_cast<int>(k), static_cast<int>(w)});
    }
  }
  std::sort(found_.begin(), found_.end());
  update_contacts(wall_contacts, found_);
}

void Simulation::compute_forces() {
  const Particles& p = particles;
  const std::size_t n = p.size();
  ContactList& pc = pair_contacts;
  const long npc = static_cast<long>(pc.size());

  // Forces per contact, each contact written by one thread only.
#pragma omp parallel for schedule(static)
  for (long k = 0; k < npc; ++k) {
    const int i = pc.slot_i[k], j = pc.slot_j[k];
    const Vec3 d = p.x[j] - p.x[i];
    const double dist = d.norm();
    ContactKinematics c;
    c.n = d / dist;
    c.overlap = p.radius[i] + p.radius[j] - dist;  // eq. 2.11
    c.v_rel = p.v[j] - p.v[i];
    c.w_arm = p.radius[j] * p.w[j] + p.radius[i] * p.w[i];
    c.m_eff = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
    const ContactForce f = CundallLaw::evaluate(materials.pair(p.material[i], p.material[j]), c, dt, pc.spring[k]);
    pc.normal[k] = c.n;
    pc.force[k] = f.on_i;
    pc.tangential[k] = f.tangential;
  }

  ContactList& wc = wall_contacts;
  const long nwc = static_cast<long>(wc.size());
  std::vector<std::vector<Vec3>> wv(walls.size());
  std::vector<Vec3> wn(walls.size()), wvel(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    wv[w] = walls[w].vertices_at(time);
    wn[w] = (wv[w][1] - wv[w][0]).cross(wv[w][2] - wv[w][0]).normalized();
    wvel[w] = walls[w].motion.velocity_at(time);
  }
#pragma omp parallel for schedule(static)
  for (long k = 0; k < nwc; ++k) {
    const int i = wc.slot_i[k], w = wc.slot_j[k];
    const Vec3 cp = closest_point_on_polygon(wv[w].data(), static_cast<int>(wv[w].size()), wn[w], p.x[i]);
    const Vec3 d = cp - p.x[i];
    const double dist = d.norm();
    ContactKinematics c;
    // A centre exactly on the wall has no direction to the contact point: use the plane normal.
    c.n = dist > 0 ? Vec3(d / dist) : wn[w];
    c.overlap = p.radius[i] - dist;  // eq. 2.17
    c.v_rel = wvel[w] - p.v[i];      // eq. 2.18: the wall's velocity enters
    c.w_arm = p.radius[i] * p.w[i];
    c.m_eff = p.mass[i];
    const ContactForce f = CundallLaw::evaluate(materials.pair(p.material[i], walls[w].material), c, dt, wc.spring[k]);
    wc.normal[k] = c.n;
    wc.force[k] = f.on_i;
    wc.tangential[k] = f.tangential;
  }

  // Per-particle lists of contact entries in a fixed order (pairs by key, then walls), so that the
  // sums below give the same bits for any thread count. Entry codes: 2k = pair contact k seen from
  // i, 2k+1 = seen from j, 2(npc+k) = wall contact k.
  csr_start_.assign(n + 1, 0);
  for (long k = 0; k < npc; ++k) ++csr_start_[pc.slot_i[k] + 1], ++csr_start_[pc.slot_j[k] + 1];
  for (long k = 0; k < nwc; ++k) ++csr_start_[wc.slot_i[k] + 1];
  for (std::size_t k = 0; k < n; ++k) csr_start_[k + 1] += csr_start_[k];
  csr_entry_.resize(csr_start_[n]);
  {
    std::vector<int> fill(csr_start_.begin(), csr_start_.end() - 1);
    for (long k = 0; k < npc; ++k) {
      csr_entry_[fill[pc.slot_i[k]]++] = static_cast<int>(2 * k);
      csr_entry_[fill[pc.slot_j[k]]++] = static_cast<int>(2 * k + 1);
    }
    for (long k = 0; k < nwc; ++k) csr_entry_[fill[wc.slot_i[k]]++] = static_cast<int>(2 * (npc + k));
  }

  force_.resize(n);
  torque_.resize(n);
  const Vec3 g = params.gravity;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < static_cast<long>(n); ++i) {
    Vec3 f = p.mass[i] * g;
    Vec3 t = Vec3::Zero();
    for (int e = csr_start_[i]; e < csr_start_[i + 1]; ++e) {
      const int code = csr_entry_[e];
      const long k = code / 2;
      // Torques, eq. 2.33-2.34: M = a n x f_t for i and j alike (M_j = (a_j / a_i) M_i).
      if (k < npc) {
        f += (code % 2 == 0) ? pc.force[k] : Vec3(-pc.force[k]);  // eq. 2.31-2.32
        t += p.radius[i] * pc.normal[k].cross(pc.tangential[k]);
      } else {
        f += wc.force[k - npc];
        t += p.radius[i] * wc.normal[k - npc].cross(wc.tangential[k - npc]);
      }
    }
    force_[i] = f;
    torque_[i] = t;
  }
}

void Simulation::integrate() {
  Particles& p = particles;
  // eq. 2.38-2.47: v^{n+1/2} = (a v^{n-1/2} + acc dt) b, a = 1 - alpha dt/2, b = 1/(1 + alpha dt/2).
  const double ar = 1 - params.alpha_r * dt / 2, br = 1 / (1 + params.alpha_r * dt / 2);
  const double at = 1 - params.alpha_theta * dt / 2, bt = 1 / (1 + params.alpha_theta * dt / 2);
  const long n = static_cast<long>(p.size());
  long bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (long i = 0; i < n; ++i) {
    p.v[i] = (ar * p.v[i] + force_[i] * (dt / p.mass[i])) * br;
    p.w[i] = (at * p.w[i] + torque_[i] * (dt / p.inertia(i))) * bt;
    p.x[i] += p.v[i] * dt;
    if (!p.x[i].allFinite() || !p.v[i].allFinite() || !p.w[i].allFinite()) bad = std::max(bad, i);
  }
  if (bad >= 0) {
    std::ostringstream m;
    m << "non-finite state at step " << step << " (t = " << time << " s) for particle id " << p.id[bad]
      << "; check the time step (dt = " << dt << " s, critical " << critical_time_step()
      << " s by eq. 2.48) and the stiffnesses";
    throw PhysicsError(m.str());
  }
}

double Simulation::critical_time_step() const {
  double mmin = std::numeric_limits<double>::infinity();
  for (double m : particles.mass) mmin = std::min(mmin, m);
  const double kmax = materials.max_stiffness();
  if (!(kmax > 0) || !std::isfinite(mmin)) return std::numeric_limits<double>::infinity();
  return 2 * std::sqrt(mmin / (2 * kmax));  // eq. 2.48 (Hart et al.), without FRAC
}

double Simulation::kinetic_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < particles.size(); ++i)
    e += 0.5 * particles.mass[i] * particles.v[i].squaredNorm() + 0.5 * particles.inertia(i) * particles.w[i].squaredNorm();
  return e;
}

std::vector<Vec3> Simulation::wall_forces() const {
  std::vector<Vec3> f(walls.size(), Vec3::Zero());
  // key_j (the wall index) is valid even before the first step after a restart, when slots are not.
  for (std::size_t k = 0; k < wall_contacts.size(); ++k) f[wall_contacts.key_j[k]] -= wall_contacts.force[k];
  return f;
}

}  // namespace dem
