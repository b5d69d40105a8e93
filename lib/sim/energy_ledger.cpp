#include "sim/energy_ledger.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "contact/kinematics.hpp"
#include "contact/model_table.hpp"
#include "core/error.hpp"
#include "forces/force_loop.hpp"
#include "sim/simulation.hpp"

namespace dem {

double EnergyLedger::scale() const {
  return reference.kinetic_translation + reference.kinetic_rotation + std::abs(reference.elastic_normal) + reference.elastic_tangential +
         reference.elastic_rolling + reference.elastic_fibres + totals.work_abs + std::abs(now.potential - reference.potential);
}

std::vector<double> EnergyLedger::values() const {
  const EnergyState* states[] = {&reference, &now};
  std::vector<double> v{have_reference ? 1.0 : 0.0};
  for (const EnergyState* s : states)
    v.insert(v.end(), {s->kinetic_translation, s->kinetic_rotation, s->potential, s->elastic_normal, s->elastic_tangential,
                       s->elastic_rolling, s->elastic_fibres});
  const EnergyTotals& t = totals;
  v.insert(v.end(), {t.damping_normal, t.tangential_work, t.global_damping, t.released, t.work_walls, t.work_prescribed, t.work_abs,
                     t.work_fluid, t.rolling_work, t.fibres_released, t.inserted});
  return v;
}

void EnergyLedger::from_values(const std::vector<double>& v) {
  if (v.size() != kValues)
    throw std::invalid_argument("holds " + std::to_string(v.size()) + " values, not " + std::to_string(kValues) +
                                " (written by an older run-stage: run the stage again from its start)");
  std::size_t k = 0;
  have_reference = v[k++] != 0;
  for (EnergyState* s : {&reference, &now})
    for (double* x : {&s->kinetic_translation, &s->kinetic_rotation, &s->potential, &s->elastic_normal, &s->elastic_tangential,
                      &s->elastic_rolling, &s->elastic_fibres})
      *x = v[k++];
  EnergyTotals& t = totals;
  for (double* x : {&t.damping_normal, &t.tangential_work, &t.global_damping, &t.released, &t.work_walls, &t.work_prescribed, &t.work_abs,
                    &t.work_fluid, &t.rolling_work, &t.fibres_released, &t.inserted})
    *x = v[k++];
}

namespace {

// What one contact adds to the step's sums.
struct ContactTerms {
  FixedSum released, elastic, springs, rolling_springs;
};

// eq. P42: what an epsd2 rolling spring holds, ½ |M|² / k_r at the half step as P31 takes it, less
// ½ M · (w_i - w_j)^{n+1/2} Δt (`w_now`): the spring turns back by k_r (w_i - w_j) Δt in the next
// step, so the change of that figure is exactly -M · w̄ Δt while the spring holds (eq. P41's work).
void account_rolling_spring(const PairParams& q, const Vec3& couple, const Vec3& w_now, double u, double r_eff, double dt, ContactTerms& t) {
  if (q.rolling != RollingLaw::ElasticPlastic) return;  // cdt holds nothing
  const double k_t = with_tangential_law(q, [&](auto law) {
    LaneKinematics<double> c{};
    c.overlap = u;
    c.r_eff = r_eff;
    return static_cast<double>(decltype(law)::stiffness_at(q, c));
  });
  t.rolling_springs.add(ElasticPlasticRolling::stored_energy(q, couple, k_t, r_eff) - 0.5 * couple.dot(w_now) * dt);
}

// eq. P43-P44: the fibres' segments. Each intact one holds ½ T² L0 / (EA) at x^n (T its tension
// of this step's force loop) plus ½ T times its stretch over the step (the P31 form: exact for the
// linear spring); one that broke this step releases what it held at the half step before.
struct FibreTerms {
  FixedSum elastic, released;
};
void account_fibres(const FibreSet& fibres, const std::vector<std::uint8_t>& broken_before, const Vec3* x0, const Vec3* v0, const Vec3* w0,
                    const Particles& p, double dt, bool measure, FibreTerms& t) {
  for (std::size_t s = 0; s < fibres.segments(); ++s) {
    const bool broke = fibres.broken[s] && s < broken_before.size() && !broken_before[s];
    if ((fibres.broken[s] || !measure) && !broke) continue;
    const int a = fibres.tie_of[s], b = a + 1;
    const int ia = fibres.tie_slot[a], ib = fibres.tie_slot[b];
    if (ia < 0 || ib < 0) continue;  // a particle removed: at a stage start, before the reference
    const Vec3 &oa = fibres.tie_offset[a], &ob = fibres.tie_offset[b];
    const Vec3 d = x0[ib] - x0[ia] + (ob - oa);  // the span at x^n (no periodic boundaries with fibres)
    const double length = d.norm(), k = fibres.stiffness[s];
    const double tension = segment_tension(k, fibres.rest[s], length);
    const double e = 0.5 * tension * tension / k;
    const Vec3 dir = d / length;
    // The stretch rate with the velocities of a half step: the tie points move with v + w x offset.
    auto stretch = [&](const Vec3* v, const Vec3* w) { return dir.dot(v[ib] + w[ib].cross(ob) - v[ia] - w[ia].cross(oa)) * dt; };
    if (broke)
      t.released.add(e - 0.5 * tension * stretch(v0, w0));
    else
      t.elastic.add(e + 0.5 * tension * stretch(p.v.data(), p.w.data()));
  }
}

// What one contact holds at the half step (eq. P31) where `measure`, and, where its bond broke this
// step, the bond's energy at the half step before, when it still held (eq. P36). `n` from i towards
// j or the wall, `u` the overlap at x^n; `dv_now`, `dv_before` = v_i - v_j (a wall: its velocity) at
// n+1/2 and n-1/2. `Normal` is the scene's normal law when all pairs share one (else MixedNormal,
// the pair's law per contact), as the force loop ran it.
template <class Normal>
void account_held(const PairParams& q, const Vec3& spring, const Vec3& n, double u, double r_eff, bool bonded, bool broke,
                  const Vec3& dv_now, const Vec3& dv_before, double dt, bool measure, ContactTerms& t) {
  with_normal_law(q.law, [&](auto law) {
    using Law = decltype(law);
    if (broke) t.released.add(Law::elastic_energy(q, u - 0.5 * n.dot(dv_before) * dt, r_eff, true));
    if (!measure) return;
    // eq. P31: at the half step n+1/2, E(u^n) + ½ f_el(u^n) Δu, Δu the overlap's change to x^{n+1}.
    bool b = bonded;
    const double f_el = Normal::elastic(q, u, r_eff, b);
    t.elastic.add(Law::elastic_energy(q, u, r_eff, bonded) + 0.5 * f_el * n.dot(dv_now) * dt);
  });
  if (measure) t.springs.add(with_tangential_law(q, [&](auto law) { return decltype(law)::stored_energy(q, spring, u, r_eff); }));
}

// One thread's share of what the ledger's pass adds; summed over the threads in FixedSum's
// integers, so the figures do not depend on how the particles and contacts were split.
struct StepSums {
  FixedSum kin_t, kin_r, potential;
  ContactTerms c;
  StepWork work;  // the particles' work other than their contacts', where the force loop did not add it
  void add(const StepSums& o) {
    kin_t.add(o.kin_t), kin_r.add(o.kin_r), potential.add(o.potential);
    c.released.add(o.c.released), c.elastic.add(o.c.elastic), c.springs.add(o.c.springs), c.rolling_springs.add(o.c.rolling_springs);
    work.add(o.work);
  }
};

}  // namespace

StepWorkInput Simulation::ledger_work_input(const FluidField* fluid, bool any_fixed) const {
  return {block_force_.data(), block_torque_.data(), fluid, params.gravity, params.alpha_r, params.alpha_theta, dt, any_fixed};
}

void Simulation::account_energy(bool any_fixed) {
  const Particles& p = particles;
  const long count = static_cast<long>(p.size());
  const Vec3* x0 = ledger_x_.data();
  const Vec3 *v0 = ledger_v_.data(), *w0 = ledger_w_.data();
  // What the particles and contacts hold is measured only where asked (and at the reference); the
  // work of the step is added every step: by the force loop (its wall contacts', and its
  // particles' where they moved in it: ledger_particles_done_), else by this pass.
  const bool measure = ledger.measures();
  std::optional<FluidField> fluid;
  if (params.fluid.on()) fluid.emplace(params.fluid);
  const StepWorkInput work_input = ledger_work_input(fluid ? &*fluid : nullptr, any_fixed);
  // The particles' work other than their contacts' (which the motion took): where any applies.
  const long particle_work_count = ledger_particles_done_ || !work_input.any() ? 0 : count, measure_count = measure ? count : 0;
  // eq. P30: the kinetic energy at the half step, the potential at the mean of x^n and x^{n+1} = x^{n+1} - v^{n+1/2} Δt/2.
  auto measure_particle = [&](std::size_t k, StepSums& s) __attribute__((always_inline)) {
    s.kin_t.add(0.5 * p.mass[k] * p.v[k].squaredNorm());
    s.kin_r.add(0.5 * p.inertia(k) * p.w[k].squaredNorm());
    s.potential.add(-p.mass[k] * params.gravity.dot(unwrapped_position(k) - 0.5 * dt * p.v[k]));
  };
  // The bonds the force loop broke this step (sorted): what they held is released.
  const bool breaks = !broken_pairs_.empty() || !broken_walls_.empty();
  const auto broke_now = [&](const std::vector<int>& broken, std::size_t k) {
    return breaks && std::binary_search(broken.begin(), broken.end(), static_cast<int>(k));
  };
  auto account_pair = [&](auto normal, std::size_t k, bool broke, ContactTerms& t) {
    // Its work this step is its particles' (the motion's: MotionWork); what it holds, where it broke or is measured.
    if (!broke && !(measure && pairs_.active[k])) [[likely]]
      return;
    const int i = pairs_.slot_i[k], j = pairs_.slot_j[k];
    const Vec3 d = periodic.any() ? separation<true>(periodic, x0[i], x0[j]) : separation<false>(periodic, x0[i], x0[j]);
    const double dist = d.norm();
    const Vec3 n = d / dist;
    const double u = p.radius[i] + p.radius[j] - dist, r_eff = effective_radius(p.radius[i], p.radius[j]);
    const PairParams& q = materials.pair(p.material[i], p.material[j]);
    account_held<decltype(normal)>(q, pairs_.spring[k], n, u, r_eff, pairs_.bonded[k], broke, p.v[i] - p.v[j], v0[i] - v0[j], dt, measure, t);
    if (measure && q.rolling != RollingLaw::None) account_rolling_spring(q, pairs_.rolling[k], p.w[i] - p.w[j], u, r_eff, dt, t);
  };
  auto account_wall = [&](auto normal, std::size_t k, bool broke, ContactTerms& t) {
    // Its work this step is the force loop's (add_wall_contact_work); what it holds, as a pair's.
    if (!broke && !(measure && walls_.active[k])) return;
    const int i = walls_.slot_i[k], w = walls_.slot_j[k];
    const WallGeometry& g = wall_geometry_[w];
    const Vec3 c = closest_point(g, x0[i]);
    const Vec3 to_wall = c - x0[i];
    const double dist = to_wall.norm();
    const Vec3 n = dist > 0 ? Vec3(to_wall / dist) : g.normal;
    const Vec3 v_wall = g.velocity_of(c);
    const PairParams& q = materials.pair(p.material[i], walls[w].material);
    const double u = p.radius[i] - dist;
    account_held<decltype(normal)>(q, walls_.spring[k], n, u, p.radius[i], walls_.bonded[k], broke, p.v[i] - v_wall, v0[i] - v_wall, dt,
                                   measure, t);
    if (measure && q.rolling != RollingLaw::None) account_rolling_spring(q, walls_.rolling[k], p.w[i] - g.spin, u, p.radius[i], dt, t);
  };
  // Each thread its own sums over fixed ranges of the particles and contacts (a term out of range
  // is kept, not thrown, and reported by value() after the region). A step with nothing to
  // measure, no bond broken and its particles' work done in the force loop needs no pass.
  StepSums sums;
  // Measuring: every contact (those that broke among them); else only those that broke.
  const bool contacts = breaks || measure;
  const long pair_count = measure ? static_cast<long>(pairs_.size()) : 0;
  const long wall_count = measure ? static_cast<long>(walls_.size()) : 0;
  const long pairs_broken = measure ? 0 : static_cast<long>(broken_pairs_.size());
  const long walls_broken = measure ? 0 : static_cast<long>(broken_walls_.size());
  auto account_all = [&](auto normal) {
#pragma omp parallel
    {
      StepSums mine;
#pragma omp for schedule(static) nowait
      for (long k = 0; k < measure_count; ++k) measure_particle(k, mine);
#pragma omp for schedule(static) nowait
      for (long lo = 0; lo < particle_work_count; lo += 1024) {
        const BeforeMotion before{x0 + lo, v0 + lo, w0 + lo};
        add_particle_work(p, work_input, before, lo, std::min(particle_work_count, lo + 1024), mine.work);
      }
#pragma omp for schedule(static) nowait
      for (long k = 0; k < pair_count; ++k) account_pair(normal, k, broke_now(broken_pairs_, k), mine.c);
#pragma omp for schedule(static) nowait
      for (long k = 0; k < wall_count; ++k) account_wall(normal, k, broke_now(broken_walls_, k), mine.c);
#pragma omp for schedule(static) nowait
      for (long e = 0; e < pairs_broken; ++e) account_pair(normal, broken_pairs_[e], true, mine.c);
#pragma omp for schedule(static) nowait
      for (long e = 0; e < walls_broken; ++e) account_wall(normal, broken_walls_[e], true, mine.c);
#pragma omp critical(dem_energy_ledger)
      sums.add(mine);
    }
  };
  // The normal law the force loop ran this step (force_loop.hpp): one for all pairs, or each pair's own.
  if (measure_count > 0 || particle_work_count > 0 || contacts) {
    if (force_variant_) with_normal_law(force_variant_->normal, account_all);
    else account_all(MixedNormal{});
  }
  const ContactTerms& t = sums.c;
  StepWork work = ledger_work_;
  work.add(sums.work);
  FibreTerms fibre_terms;
  if (!fibres.empty()) account_fibres(fibres, ledger_fibre_broken_, x0, v0, w0, p, dt, measure, fibre_terms);

  EnergyLedger& l = ledger;
  if (measure)
    l.now = EnergyState{sums.kin_t.value(), sums.kin_r.value(),     sums.potential.value(),      t.elastic.value(),
                        t.springs.value(), t.rolling_springs.value(), fibre_terms.elastic.value()};
  if (!l.have_reference) {  // the first step accounted is the reference: its own work is not counted
    l.reference = l.now;
    l.totals = EnergyTotals{};
    l.have_reference = true;
    return;
  }
  EnergyTotals& s = l.totals;
  const double walls_in = work.walls.value(), prescribed_in = work.prescribed.value(), fluid_in = work.fluid.value();
  s.damping_normal += work.damping.value();
  s.tangential_work += work.tangential.value();
  s.global_damping += work.global.value();
  s.released += t.released.value();
  s.work_walls += walls_in;
  s.work_prescribed += prescribed_in;
  s.work_fluid += fluid_in;
  s.rolling_work += work.rolling.value();
  s.fibres_released += fibre_terms.released.value();
  s.work_abs += std::abs(walls_in) + std::abs(prescribed_in) + std::abs(fluid_in);
}

void Simulation::account_inserted(std::size_t first) {
  EnergyLedger& l = ledger;
  if (!l.on || !l.have_reference) return;  // before the reference, the reference takes them in
  // eq. P45: each as the ledger will count it, kinetic energy at v^{n-1/2} and potential energy at
  // x^n - v Δt/2 (the mean of x^{n-1} and x^n had it moved with v), so that its first step's
  // change is its first step's work.
  const Particles& p = particles;
  FixedSum in;
  for (std::size_t k = first; k < p.size(); ++k)
    in.add(0.5 * p.mass[k] * p.v[k].squaredNorm() + 0.5 * p.inertia(k) * p.w[k].squaredNorm() -
           p.mass[k] * params.gravity.dot(unwrapped_position(k) - 0.5 * dt * p.v[k]));
  const double e = in.value();
  l.totals.inserted += e;
  l.totals.work_abs += std::abs(e);
}

}  // namespace dem
