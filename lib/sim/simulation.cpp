#include "sim/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <omp.h>

#include "contact/model_table.hpp"
#include "forces/force_loop.hpp"
#include "integrate/motion.hpp"
#include "simd/simd.hpp"
#include "core/error.hpp"

namespace dem {

namespace {
bool motion_apart_for_tests = false;  // set_motion_apart_for_tests
}  // namespace

void set_motion_apart_for_tests(bool apart) { motion_apart_for_tests = apart; }

namespace {
// One thread for the scope where `on` (SimParams::parallel_min_particles), then the count before.
class OneThreadIf {
 public:
  explicit OneThreadIf(bool on) : before_(on ? omp_get_max_threads() : 0) {
    if (on) omp_set_num_threads(1);
  }
  ~OneThreadIf() {
    if (before_ > 0) omp_set_num_threads(before_);
  }
  OneThreadIf(const OneThreadIf&) = delete;
  OneThreadIf& operator=(const OneThreadIf&) = delete;

 private:
  int before_;
};
}  // namespace

void Simulation::advance() {
  const OneThreadIf small(static_cast<long>(particles.size()) < params.parallel_min_particles);
  step_threads_ = omp_get_max_threads();
  // Also at a run's first step: a checkpoint holds the particles by id, which puts neighbours
  // anywhere in storage until the next sort (up to sort_every steps).
  if (params.sort_every > 0 && (step % params.sort_every == 0 || !storage_sorted_) &&
      static_cast<long>(particles.size()) >= params.sort_min_particles)
    sort_storage();
  const bool any_fixed = particles.any_fixed();
  const bool any_prescribed = any_fixed && particles.any_prescribed();
  const bool audit = energy_check_on();
  // The fibres' forces are added after the force loop, and the energy check's reference step reads
  // the contacts' stored energy before the motion: otherwise the motion joins the force loop
  // (ForceBlocks::motion), each block's state kept for the energy ledger as it moves, and on the
  // check's other measuring steps each block's energy taken before it moves.
  if (fibres.empty() && !(audit && energy_check_takes_reference()) && !motion_apart_for_tests) {
    // The ledger's pass after the step reads the state before the motion only where it measures
    // or a bond may break; otherwise each block keeps its own while it moves (block_forces.hpp).
    const bool ledger_reads_state = ledger.on && (ledger.measures() || has_bonds_);
    const MotionStep motion = motion_step(any_fixed, ledger_reads_state);
    compute_loads(&motion, audit && energy_check_measures_now());
    if (audit) audit_energy(any_prescribed);  // the work of the step only: the walls' from the force loop
  } else {
    compute_forces();
    if (audit) audit_energy(any_prescribed);
    integrate(any_fixed, ledger.on);
  }
  if (ledger.on) account_energy(any_fixed);
  if (!fibres.empty()) rotate_ties(fibres, particles, dt);  // the ties turn with their particles
  time += dt;
  ++step;
  if (has_bonds_) {  // bonds only ever break: stop paying once all are gone
    bonds_ -= static_cast<long>(broken_pairs_.size() + broken_walls_.size());
    has_bonds_ = bonds_ > 0;
  }
}

void Simulation::compute_forces() { compute_loads(nullptr, false); }

void Simulation::compute_loads(const MotionStep* motion, bool measure_energy) {
  find_contacts();
  const bool any_fixed = particles.any_fixed();
  if (ledger.on) {  // the contacts' work for the energy ledger, per contact and per particle
    ledger_contact_work_.resize(pairs_.size());
    ledger_wall_work_.resize(walls_.size());
    ledger_particle_work_.resize(particles.size());
  }
  if (wall_rank_.size() != walls_.size()) rank_wall_candidates();
  const bool copy_wall_forces = wall_loads_asked_;
  if (copy_wall_forces && !wall_forces_written_)
    for (WallForce& w : wall_forces_) w.active = 0;  // stale: the loop only writes what changes
  const ForceLoopInput in{particles, materials, wall_geometry_, wall_runs_, wall_run_order_, wall_block_first_, periodic,
                          any_fixed, has_bonds_, dt, params.keep_pair_results,
                          ledger.on ? ledger_contact_work_.data() : nullptr, ledger.on ? ledger_wall_work_.data() : nullptr,
                          ledger.on && !ledger_work_zeros_, wall_rank_.data(),
                          copy_wall_forces ? wall_forces_.data() : nullptr};
  ledger_work_zeros_ = ledger.on;  // pass 1 zeroes it now, and keeps it so while the log stays on
  if (indexed_block_ != params.load_block) index_contacts_per_particle();
  const bool sum_wall_power = walls_move_ && energy_check_on();  // the energy check's (audit_energy)
  if (sum_wall_power) wall_power_.assign(block_first_.size() - 1, 0.0);  // per load block (ForceBlocks::wall_power)
  block_force_.resize(particles.size());
  block_torque_.resize(particles.size());
  const bool fluid = params.fluid.on();
  if (fluid) update_fluid_grains();
  const BodyForces body{params.gravity, fluid ? &params.fluid : nullptr, &fluid_grains_};
  ForceBlocks loads{params.load_block, block_first_, block_needs_, needed_from_, by_key_start_, by_key_split_, by_key_, force_times_,
                    block_done_,       touched_,       ++force_epoch_, body, simd_loops_on(), block_force_, block_torque_,
                    ledger.on ? ledger_particle_work_.view() : ParticleWork{}, sum_wall_power ? wall_power_.data() : nullptr,
                    motion};
  check_energy_in_loop_ = motion && measure_energy;
  if (check_energy_in_loop_) {
    check_energy_.assign(block_first_.size() - 1, MechanicalEnergy{});
    loads.energy_before_motion = check_energy_.data();
  }
  broken_pairs_.clear(), broken_walls_.clear();
  loads.broken_pairs = &broken_pairs_, loads.broken_walls = &broken_walls_;
  force_variant_ = choose_force_variant(materials, has_bonds());
  // The energy log: the step's work added where it arises, the particles' as each block moves.
  StepWorkInput particle_work;
  ledger_work_ = StepWork{};
  ledger_particles_done_ = ledger.on && motion;
  if (ledger.on) loads.step_work = &ledger_work_;
  if (ledger_particles_done_) {
    particle_work = ledger_work_input(fluid ? &*body.fluid : nullptr, any_fixed);
    loads.particle_work = &particle_work;
  }
  const double worst_overlap = compute_contact_forces(in, force_variant_, pairs_, walls_, loads);
  // Fibres: a force source after the contacts and body forces (one serial loop over segments).
  if (!fibres.empty()) {
    if (ledger.on) ledger_fibre_broken_ = fibres.broken;  // those that break now release their energy (eq. P44)
    add_fibre_forces(fibres, particles, periodic, block_force_, block_torque_);
  }
  pair_results_kept_ = params.keep_pair_results;
  contacts_modified();
  wall_forces_current_ = wall_forces_written_ = copy_wall_forces;  // every candidate's, where written
  wall_loads_asked_ = false;
  if (worst_overlap > params.max_overlap) report_overlap(worst_overlap);
  if (loads.not_finite >= 0) report_not_finite(loads.not_finite);
}

void Simulation::update_fluid_grains() {
  const long n = static_cast<long>(particles.size());
  if (static_cast<long>(particles.void_fraction.size()) != n || step % params.fluid.void_every == 0) {
    void_fractions(particles, periodic, params.fluid.void_cutoff, void_scratch_, particles.void_fraction);
    fluid_grains_.clear();
  }
  const double mu = params.fluid.viscosity, rho = params.fluid.density;
  if (fluid_grains_.size() == n && fluid_grains_for_[0] == mu && fluid_grains_for_[1] == rho) return;
  // Each grain's from its radius and void fraction alone: a resumed run rebuilds the same bits.
  const FluidField field(params.fluid);
  fluid_grains_.resize(n);
  fluid_grains_for_[0] = mu, fluid_grains_for_[1] = rho;
#pragma omp parallel for schedule(static) if (n > 1024)
  for (long i = 0; i < n; ++i) fluid_grains_.set(i, field.grain(particles.radius[i], particles.void_fraction[i]));
}

const ContactList& Simulation::pair_contacts() const {
  if (!pair_view_current_) {
    active_contacts(pairs_, pair_key_order(), pair_view_);
    pair_view_current_ = true;
  }
  return pair_view_;
}

const ContactList& Simulation::wall_contacts() const {
  if (!wall_view_current_) {
    active_contacts(walls_, wall_by_key_, wall_view_);
    wall_view_current_ = true;
  }
  return wall_view_;
}

std::size_t Simulation::pair_contact_count() const { return active_count(pairs_); }
std::size_t Simulation::wall_contact_count() const { return active_count(walls_); }

void Simulation::release_contact_views() const {
  pair_view_ = ContactList();  // move-assigned from an empty list: the storage is freed
  wall_view_ = ContactList();
  pair_view_current_ = wall_view_current_ = false;
}

void Simulation::contacts_modified() { pair_view_current_ = wall_view_current_ = wall_forces_current_ = false; }

void Simulation::rank_wall_candidates() {
  const std::size_t n = walls_.size();
  wall_rank_.resize(n);
  wall_forces_.assign(n, WallForce{});
  for (std::size_t r = 0; r < n; ++r) {
    const int k = key_rank_to_position(wall_by_key_, r);
    wall_rank_[k] = static_cast<int>(r);
    wall_forces_[r].wall = static_cast<std::int32_t>(walls_.key_j[k]);
  }
}

void Simulation::set_contacts(ContactList pairs, ContactList walls) {
  pairs_ = std::move(pairs);
  walls_ = std::move(walls);
  pair_by_key_.clear(), wall_by_key_.clear();  // given in key order
  pair_by_key_current_ = true;
  pair_results_kept_ = true;  // those given
  for (ContactList* c : {&pairs_, &walls_}) {
    c->resize(c->size());  // fields a caller left empty
    std::fill(c->active.begin(), c->active.end(), 1);
    std::fill(c->slot_i.begin(), c->slot_i.end(), -1);
    std::fill(c->slot_j.begin(), c->slot_j.end(), -1);
  }
  neighbours_ = NeighbourList();  // the next step finds the candidates and carries this history over
  contacts_modified();
  energy_.valid = false;  // particles or contacts changed: the energy check takes a new reference
  count_bonds();
}

namespace {
// A key order (KeyOrder) of a list from which some entries were removed, `place` the new position
// of each entry (-1: removed); an empty order (the list stored in key order) stays so.
KeyOrder kept_in_key_order(const KeyOrder& by_key, const std::vector<int>& place) {
  KeyOrder out;
  out.reserve(by_key.size());
  for (int k : by_key)
    if (place[k] >= 0) out.push_back(place[k]);
  return out;
}
}  // namespace

bool Simulation::remove_from_lists(const std::vector<char>& gone) {
  const std::size_t n = particles.size();
  if (!neighbours_.valid_for(n) || gone.size() != n) return false;
  std::vector<int> slot(n, -1);  // each particle's slot once the others are gone
  int left = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (!gone[k]) slot[k] = left++;
  // Each list's entries of particles left, renumbered, in their order: still grouped by the smaller
  // slot in slot order (the renumbering keeps the slots' order), as the force loop reads them.
  const auto filter = [&](ContactList& list, KeyOrder& by_key, bool pairs) {
    std::vector<int> place(list.size(), -1);
    int next = 0;
    for (std::size_t k = 0; k < list.size(); ++k)
      if (slot[list.slot_i[k]] >= 0 && (!pairs || slot[list.slot_j[k]] >= 0)) place[k] = next++;
    by_key = kept_in_key_order(by_key, place);
    list.keep_only(Kept(list.size(), [&](std::size_t k) { return place[k] >= 0; }));
    for (int& i : list.slot_i) i = slot[i];
    if (pairs)
      for (int& j : list.slot_j) j = slot[j];
    return place;  // each entry's new position, -1 where gone
  };
  if (!pair_by_key_current_) pair_by_key_.clear();  // sorted again when asked
  const std::vector<int> pair_place = filter(pairs_, pair_by_key_, true);
  filter(walls_, wall_by_key_, false);
  const Kept stay(n, [&](std::size_t k) { return slot[k] >= 0; });
  particles.keep_only(stay);
  neighbours_.keep_only(stay);
  if (fluid_grains_.size() == static_cast<long>(n)) fluid_grains_.keep_only(stay);
  rank_wall_candidates();
  const Renumbering renumbered{slot, pair_place};
  index_contacts_per_particle(&renumbered);
  count_bonds();
  contacts_modified();
  ledger_work_zeros_ = false;  // the ledger's per-candidate arrays are sized anew
  energy_.valid = false;       // particles changed: the energy check takes a new reference
  return true;
}

void Simulation::report_overlap(double worst) const {
  // Name the contact(s) with the largest overlap, recomputed as the force loop does (where the
  // step's motion joined the force loop, the particles have moved since: then it names those with
  // the largest overlap after it, most often the same); runs once, on failure.
  const Particles& p = particles;
  std::ostringstream m;
  m << "overlap of " << worst * 100 << " % of the radius (limit simulation.max_overlap = " << params.max_overlap * 100
    << " %) at step " << step << " (t = " << time << " s), ";
  const KeyOrder& by_key = pair_key_order();
  const auto pair_overlap = [&](int k) {
    const int i = pairs_.slot_i[k], j = pairs_.slot_j[k];
    return (p.radius[i] + p.radius[j] - separation(p, periodic, i, j).norm()) / std::min(p.radius[i], p.radius[j]);
  };
  const auto wall_overlap = [&](std::size_t k) {
    const int i = walls_.slot_i[k];
    return (p.radius[i] - (closest_point(wall_geometry_[walls_.slot_j[k]], p.x[i]) - p.x[i]).norm()) / p.radius[i];
  };
  double largest = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < pairs_.size(); ++k)
    if (pairs_.active[k]) largest = std::max(largest, pair_overlap(static_cast<int>(k)));
  for (std::size_t k = 0; k < walls_.size(); ++k)
    if (walls_.active[k]) largest = std::max(largest, wall_overlap(k));
  for (std::size_t r = 0; r < pairs_.size(); ++r) {
    const int k = key_rank_to_position(by_key, r);
    if (pairs_.active[k] && pair_overlap(k) == largest)
      m << "between particles " << p.id[pairs_.slot_i[k]] << " and " << p.id[pairs_.slot_j[k]] << ", ";
  }
  for (std::size_t r = 0; r < walls_.size(); ++r) {
    const int k = key_rank_to_position(wall_by_key_, r);
    if (walls_.active[k] && wall_overlap(k) == largest)
      m << "between particle " << p.id[walls_.slot_i[k]] << " and wall " << walls[walls_.slot_j[k]].name << ", ";
  }
  m << "with dt = " << dt << " s against the critical " << critical_time_step()
    << " s of docs/physics.md eq. P5";
  throw PhysicsError(m.str(), "lower the time step (frac), raise the stiffness kn, or lower the load or impact speed");
}

std::size_t Simulation::bond_present_contacts(bool walls_too, double gap) {
  find_contacts();
  // The pairs touching now (the test of the force loop) or apart by less than the gap, and the
  // contacts holding already. The neighbour list holds every pair within the skin, which is far
  // wider than a gap of round-off.
  const Particles& p = particles;
  std::size_t n = 0;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const int i = pairs_.slot_i[k], j = pairs_.slot_j[k];
    if (p.both_fixed(i, j)) continue;
    const bool near = pair_touching(p, periodic, i, j) ||
                      (gap > 0 && spheres_touch(separation(p, periodic, i, j), p.radius[i] + gap * std::min(p.radius[i], p.radius[j]), p.radius[j]));
    if (near || pairs_.bonded[k]) pairs_.bonded[k] = pairs_.active[k] = 1, ++n;
  }
  if (walls_too) {
    // Per particle, the touches the force loop counts (select_wall_contacts): where mesh elements
    // meet, one touch seen by two elements is one contact and gets one bond.
    std::vector<Vec3> to_wall;
    std::vector<std::uint8_t> touching, take;
    std::vector<int> order;
    for (std::size_t r = 0; r + 1 < wall_runs_.size(); ++r) {
      const int first = wall_runs_[r], count = wall_runs_[r + 1] - first;
      to_wall.resize(count), touching.resize(count), take.resize(count), order.resize(count);
      counted_wall_touches(p, wall_geometry_, walls_, first, count, to_wall.data(), touching.data(), take.data(), order.data(), gap);
      for (int e = 0; e < count; ++e)
        if (take[e] || walls_.bonded[first + e]) walls_.bonded[first + e] = walls_.active[first + e] = 1, ++n;
    }
  }
  contacts_modified();
  count_bonds();
  return n;
}

void Simulation::count_bonds() {
  bonds_ = bond_count();
  has_bonds_ = bonds_ > 0;
}

long Simulation::bond_count() const {
  // The sum of the flags, which falls whenever one is cleared: a plain sum of bytes, vectorised.
  const auto sum = [](const std::vector<std::uint8_t>& flags) {
    long n = 0;
    for (std::uint8_t b : flags) n += b;
    return n;
  };
  return sum(pairs_.bonded) + sum(walls_.bonded);
}

void Simulation::update_wall_geometry() {
  wall_geometry_.resize(walls.size());
  const long nw = static_cast<long>(walls.size());
  bool moving = false;
#pragma omp parallel if (nw > 1000) reduction(|| : moving)
  {
    RotationCache rotations;
#pragma omp for schedule(static)
    for (long w = 0; w < nw; ++w) {
      place_wall(walls[w], time, dt, wall_geometry_[w], rotations);
      moving = moving || !wall_geometry_[w].velocity.isZero(0) || !wall_geometry_[w].spin.isZero(0);
    }
  }
  walls_move_ = moving;
}

void Simulation::set_periodic(const PeriodicBox& box) {
  Particles& p = particles;
  if (!(box == periodic)) {  // a new period: images of the old one mean nothing in it
    for (std::size_t k = 0; k < p.size(); ++k) p.x[k] = unwrapped_position(k), p.image[k] = Vec3i::Zero();
    periodic = box;
  }
  for (std::size_t k = 0; k < p.size(); ++k) periodic.wrap_far(p.x[k], p.image[k]);
  neighbours_.invalidate();
}

void Simulation::sort_storage() {
  // Cells of edge one largest diameter (at most 2^20 per axis), row by row; within a cell the old
  // order.
  const Particles& p = particles;
  const std::size_t n = p.size();
  if (n == 0) return;
  Vec3 lo = p.x[0], hi = p.x[0];
  double rmax = 0;
  for (std::size_t k = 0; k < n; ++k) lo = lo.cwiseMin(p.x[k]), hi = hi.cwiseMax(p.x[k]), rmax = std::max(rmax, p.radius[k]);
  if (!lo.allFinite() || !hi.allFinite() || !(rmax > 0)) return;  // integrate() reports non-finite states
  constexpr double kMaxCells = 1 << 20;
  std::array<double, 3> edge;
  std::array<std::int64_t, 3> dims;
  for (int d = 0; d < 3; ++d) {
    edge[d] = std::max(2 * rmax, (hi[d] - lo[d]) / kMaxCells);
    dims[d] = static_cast<std::int64_t>(std::min(kMaxCells, (hi[d] - lo[d]) / edge[d])) + 1;
  }
  // The axis with the most cells varies slowest (z first where the counts tie): neighbours across
  // it then lie a layer of the other two axes' cells apart in storage, the fewest there are (a thin
  // slab ordered along its thin axis first put a particle's neighbours a quarter of the slab apart).
  std::array<int, 3> axis{2, 1, 0};
  std::stable_sort(axis.begin(), axis.end(), [&](int a, int b) { return dims[a] > dims[b]; });
  std::vector<std::pair<std::int64_t, std::size_t>> key(n);
#pragma omp parallel for schedule(static)
  for (long k = 0; k < static_cast<long>(n); ++k) {
    std::array<std::int64_t, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = static_cast<std::int64_t>(std::min<double>(dims[d] - 1, (p.x[k][d] - lo[d]) / edge[d]));
    key[k] = {(c[axis[0]] * dims[axis[1]] + c[axis[1]]) * dims[axis[2]] + c[axis[2]], static_cast<std::size_t>(k)};
  }
  std::sort(key.begin(), key.end());  // (cell, old slot): unique keys, one order for any thread count
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = key[k].second;
  particles.reorder(order);
  storage_sorted_ = true;
  // The slots in the lists are stale: the next search rebuilds them (history is kept by ids).
  neighbours_.invalidate();
  fluid_grains_.clear();  // rebuilt in the new order from the void fractions, which moved with their particles
}

void Simulation::find_contacts() {
  // Bonded pairs hold in tension until they break: list that much further while bonds exist.
  const double margin = has_bonds_ ? 1.01 * materials.max_break_separation() : 0.0;
  update_wall_geometry();
  if (!neighbours_.update(particles, periodic, wall_geometry_, margin, params.skin)) return;
  ledger_work_zeros_ = false;  // new candidates
  // New candidates: carry the history over by key; which pairs touch is decided by the force loop.
  // Both lists are stored along the particles' storage order (locality when the storage is sorted):
  // pairs as the search finds them, wall candidates each particle's in one run, in key order.
  if (carry_history_in_groups(pairs_, neighbours_.pairs(), neighbours_.pair_groups(), particles.id, carry_from_)) {
    pair_by_key_current_ = false;
  } else {  // the slots changed since the last build: carry by key (a sort of the candidates)
    KeyOrder& old_by_key = pair_key_order();
    neighbours_.sort_pairs_by_key();
    place_by_storage(neighbours_.pairs(), particles.size(), place_count_, pair_place_);
    carry_history(pairs_, old_by_key, neighbours_.pairs(), pair_place_, carry_from_);
  }
  place_walls_by_storage(neighbours_.wall_pairs(), particles.size(), place_count_, wall_place_);
  carry_history(walls_, wall_by_key_, neighbours_.wall_pairs(), wall_place_, carry_from_);
  rank_wall_candidates();
  neighbours_.release_found();  // carried over: free the memory until the next rebuild
  index_contacts_per_particle();
  if (has_bonds_) count_bonds();  // a bonded candidate the search no longer lists is gone with its bond
}

KeyOrder& Simulation::pair_key_order() const {
  if (!pair_by_key_current_) sort_by_key(pairs_, pair_by_key_);
  pair_by_key_current_ = true;
  return pair_by_key_;
}

void Simulation::index_contacts_per_particle(const Renumbering* removal) {
  if (params.load_block < 1) throw std::invalid_argument("SimParams::load_block must be at least 1");
  const std::size_t n = particles.size();
  const long npc = static_cast<long>(pairs_.size());
  const long nwc = static_cast<long>(walls_.size());
  // Load blocks: candidates are stored grouped by their smaller slot, in slot order
  // (place_by_storage), so each block's candidates form one run.
  const long block = params.load_block;
  const long blocks = (static_cast<long>(n) + block - 1) / block;
  auto lower_slot = [&](long k) { return std::min(pairs_.slot_i[k], pairs_.slot_j[k]); };
  // Each block's first candidate by bisection; the order is checked below (each candidate lies in
  // the block whose run holds it, the runs in order).
  block_first_.resize(blocks + 1);
  for (long b = 0; b <= blocks; ++b) {
    long lo = 0, hi = npc;  // the first candidate whose smaller slot lies in block b or later
    while (lo < hi) {
      const long mid = lo + (hi - lo) / 2;
      if (lower_slot(mid) < b * block) lo = mid + 1;
      else hi = mid;
    }
    block_first_[b] = lo;
  }
  indexed_block_ = block;
  bool ordered = block_first_[blocks] == npc;
  for (long b = 0; b < blocks; ++b) ordered = ordered && block_first_[b] <= block_first_[b + 1];
#pragma omp parallel for schedule(static) reduction(&& : ordered)
  for (long b = 0; b < blocks; ++b)
    for (long k = block_first_[b]; k < block_first_[b + 1]; ++k)
      ordered = ordered && lower_slot(k) >= b * block && lower_slot(k) < (b + 1) * block;
  if (!ordered) throw std::logic_error("pair candidates not stored along the slots");
  if (removal) keep_contacts_per_particle(*removal);
  else list_contacts_per_particle();
  const long slots = static_cast<long>(n);
  // Per block, the first block whose group holds a candidate of its particles (the group of a
  // candidate is the block of its smaller slot: this block or an earlier one).
  block_needs_.resize(blocks);
#pragma omp parallel for schedule(static)
  for (long b = 0; b < blocks; ++b) {
    long needs = b;
    for (long e = by_key_start_[b * block]; e < by_key_start_[std::min(slots, (b + 1) * block)]; ++e)
      needs = std::min(needs, static_cast<long>(lower_slot(by_key_[e])) / block);
    block_needs_[b] = needs;
  }
  needed_from_.resize(blocks);
  for (long b = blocks - 1, least = blocks; b >= 0; --b) needed_from_[b] = least = std::min(least, block_needs_[b]);
  // Wall candidates are grouped by particle slot: each particle's form one run, taken together by
  // the wall force loop (where mesh elements meet, one touch must count once).
  wall_runs_.clear();
  for (long k = 0; k < nwc; ++k)
    if (k == 0 || walls_.key_i[k] != walls_.key_i[k - 1]) wall_runs_.push_back(static_cast<int>(k));
  wall_runs_.push_back(static_cast<int>(nwc));
  // The force loop takes them by storage slot, block by block (each thread those of its blocks).
  const int runs = static_cast<int>(wall_runs_.size()) - 1;
  wall_run_order_.resize(runs);
  std::iota(wall_run_order_.begin(), wall_run_order_.end(), 0);
  const auto slot_of_run = [&](int r) { return walls_.slot_i[wall_runs_[r]]; };
  std::sort(wall_run_order_.begin(), wall_run_order_.end(), [&](int a, int b) { return slot_of_run(a) < slot_of_run(b); });
  wall_block_first_.resize(blocks + 1);
  for (long b = 0, q = 0; b <= blocks; ++b) {
    while (q < runs && slot_of_run(wall_run_order_[q]) < b * block) ++q;
    wall_block_first_[b] = static_cast<int>(q);
  }
}

void Simulation::list_contacts_per_particle() {
  const std::size_t n = particles.size();
  const long npc = static_cast<long>(pairs_.size());
  const long slots = static_cast<long>(n);
  // Per-particle lists of the pair candidates by which the force loop sums each particle's
  // contacts (ForceBlocks): first those where it is i, then those where it is j, each run in the
  // order of the contacts' keys: the same bits for any thread count and any storage order.
  by_key_start_.assign(n + 1, 0);
  by_key_split_.assign(n, 0);
  for (long k = 0; k < npc; ++k) ++by_key_start_[pairs_.slot_i[k] + 1], ++by_key_start_[pairs_.slot_j[k] + 1], ++by_key_split_[pairs_.slot_i[k]];
  for (std::size_t k = 0; k < n; ++k) by_key_start_[k + 1] += by_key_start_[k], by_key_split_[k] += by_key_start_[k];
  if (static_cast<std::size_t>(by_key_start_[n]) > by_key_.capacity()) by_key_.reserve(by_key_start_[n]);  // no doubling
  by_key_.resize(by_key_start_[n]);
  by_key_fill_.assign(by_key_start_.begin(), by_key_start_.end() - 1);
  std::vector<int>& j_fill = by_key_fill_j_;
  j_fill = by_key_split_;
  for (long k = 0; k < npc; ++k) {
    by_key_[by_key_fill_[pairs_.slot_i[k]]++] = static_cast<int>(k);
    by_key_[j_fill[pairs_.slot_j[k]]++] = static_cast<int>(k);
  }
  const auto before = [&](int a, int b) { return key_before(pairs_, a, b); };
#pragma omp parallel for schedule(static, 1024)
  for (long s = 0; s < slots; ++s) {
    std::sort(by_key_.begin() + by_key_start_[s], by_key_.begin() + by_key_split_[s], before);
    std::sort(by_key_.begin() + by_key_split_[s], by_key_.begin() + by_key_start_[s + 1], before);
  }
}

void Simulation::keep_contacts_per_particle(const Renumbering& removal) {
  // A kept particle's candidates left keep their keys, so their order: its list is its old one
  // without the removed candidates, renumbered; nothing is sorted again.
  const std::vector<int>&slot = removal.slot, &place = removal.place;
  const long old_slots = static_cast<long>(slot.size());
  const std::size_t n = particles.size();
  if (by_key_start_.size() != slot.size() + 1 || by_key_.size() != 2 * place.size())
    throw std::logic_error("per-particle lists not built for the candidates before the removal");
  std::vector<int> start(n + 1, 0), split(n, 0);
#pragma omp parallel for schedule(static)
  for (long s = 0; s < old_slots; ++s) {
    if (slot[s] < 0) continue;
    int as_i = 0, all = 0;
    for (int e = by_key_start_[s]; e < by_key_start_[s + 1]; ++e) {
      const int kept = place[by_key_[e]] >= 0;
      all += kept, as_i += e < by_key_split_[s] ? kept : 0;
    }
    start[slot[s] + 1] = all, split[slot[s]] = as_i;
  }
  for (std::size_t k = 0; k < n; ++k) start[k + 1] += start[k];
  std::vector<int> by_key(start[n]);
#pragma omp parallel for schedule(static)
  for (long s = 0; s < old_slots; ++s) {
    if (slot[s] < 0) continue;
    int out = start[slot[s]];
    split[slot[s]] += out;
    for (int e = by_key_start_[s]; e < by_key_start_[s + 1]; ++e)
      if (place[by_key_[e]] >= 0) by_key[out++] = place[by_key_[e]];
  }
  by_key_start_.swap(start), by_key_split_.swap(split), by_key_.swap(by_key);
}

MotionStep Simulation::motion_step(bool any_fixed, bool keep_state) {
  // eq. 2.38-2.47: v^{n+1/2} = (a v^{n-1/2} + acc dt) b, a = 1 - alpha dt/2, b = 1/(1 + alpha dt/2).
  const MotionConstants c{1 - params.alpha_r * dt / 2, 1 / (1 + params.alpha_r * dt / 2), 1 - params.alpha_theta * dt / 2,
                          1 / (1 + params.alpha_theta * dt / 2), dt, periodic};
  Particles& p = particles;
  block_force_.resize(p.size());  // the loads the force loop sums (compute_loads)
  block_torque_.resize(p.size());
  MotionArrays a{.x = p.x.data(),
                       .v = p.v.data(),
                       .w = p.w.data(),
                       .image = p.image.data(),
                       .mass = p.mass.data(),
                       .radius = p.radius.data(),
                       .fixed = any_fixed ? p.fixed.data() : nullptr,
                       .force = block_force_.data(),
                       .torque = block_torque_.data()};
  if (keep_state) {  // the energy ledger's x^n, v^{n-1/2}, w^{n-1/2}
    ledger_x_.resize(p.size()), ledger_v_.resize(p.size()), ledger_w_.resize(p.size());
    a.before_x = ledger_x_.data(), a.before_v = ledger_v_.data(), a.before_w = ledger_w_.data();
  }
  return {a, c};
}

void Simulation::integrate(bool any_fixed, bool keep_state) {
  const MotionStep step_motion = motion_step(any_fixed, keep_state);
  const MotionArrays a = step_motion.arrays;
  const MotionConstants c = step_motion.constants;
  const long n = static_cast<long>(particles.size());
  long bad = -1;
  // Each thread takes a contiguous run of blocks of particles (load_block slots each) sized by
  // their times at the last step (core/block_times.hpp): close to its run in the force loop, so its
  // particles' loads and positions are in its core's cache. (Split evenly, a thread read half its
  // particles from the other core's cache.)
  const long block = params.load_block;
  const long blocks = (n + block - 1) / block;
  integrate_times_.fit(blocks, [&](long b) { return std::min(block, n - b * block); });  // particles, until timed
  // With the energy log, the contacts' work of the particles as they move (MotionWork), from the
  // force loop's per-slot sums, each thread's into its own sums, added in FixedSum's integers.
  const bool work = ledger.on;
  const bool couples = !force_variant_ || force_variant_->rolling != RollingLaw::None;  // else no couples were summed
  const ParticleWork sums = work ? ledger_particle_work_.view() : ParticleWork{};
  // Each thread takes its own copies of these (firstprivate), kept in registers: shared, they are
  // read through OpenMP's record of shared variables, which the compiler reloaded after every store
  // (Eigen's stores are SSE intrinsics, which may alias anything; bench/results/design.md).
#pragma omp parallel reduction(max : bad) firstprivate(a, c)
  {
    const long threads = omp_get_num_threads(), t = omp_get_thread_num();
    const long start = integrate_times_.run_start(t, threads), end = integrate_times_.run_start(t + 1, threads);
    StepWork mine;
    for (long b = start; b < end; ++b) {
      const long tb = BlockTimes::now();
      const long lo = b * block, hi = std::min(n, lo + block);
      const MotionWork block_work{sums.from(lo), couples, &mine};
      bad = std::max(bad, move_particles(a, c, lo, hi, work ? &block_work : nullptr));
      integrate_times_.record(b, tb);
    }
    if (work) {
#pragma omp critical(dem_integrate_work)
      ledger_work_.add(mine);  // exact: in any order
    }
  }
  if (bad >= 0) report_not_finite(bad);
}

void Simulation::report_not_finite(long slot) const {
  std::ostringstream m;
  m << "non-finite state at step " << step << " (t = " << time << " s) for particle id " << particles.id[slot] << ", with dt = " << dt
    << " s against the critical " << critical_time_step() << " s of docs/physics.md eq. P5";
  throw PhysicsError(m.str(), "check the time step and the stiffnesses");
}

// The fluid does work the energy balance does not hold (docs/physics.md, "Fluid drag"): no check then.
bool Simulation::energy_check_on() const { return params.max_energy_gain > 0 && !params.fluid.on(); }

bool Simulation::energy_check_takes_reference() const {
  const EnergyBalance& b = energy_;
  return !b.valid || b.particles != particles.size();
}

bool Simulation::energy_check_measures_now() const {
  return energy_check_takes_reference() || (step - energy_.step0) % kEnergyCheckEvery == 0;
}

MechanicalEnergy Simulation::energy_before_motion() const {
  // The force loop's sums where it took them (compute_loads), else the same runs of slots summed here.
  return check_energy_in_loop_ ? sum_in_order(check_energy_) : mechanical_energy(particles, params.gravity, periodic, nullptr, params.load_block);
}

void Simulation::audit_energy(bool any_prescribed) {
  // Called with the forces at x^n computed; on the steps it measures (energy_check_measures_now),
  // before the motion: the velocities still at n-1/2 (sim/energy_audit.hpp).
  EnergyBalance& b = energy_;
  if (!b.valid || b.particles != particles.size()) {
    b = EnergyBalance{};
    b.valid = true;
    b.step0 = step;
    b.particles = particles.size();
    b.start = b.now = energy_before_motion();
    b.stored0 = stored_energy_bound(particles, materials, walls, wall_geometry_, periodic, pairs_, walls_);
    if (!fibres.empty()) b.stored0 += fibres.elastic_energy(particles, periodic);
    for (std::size_t k = 0; k < particles.size(); ++k) b.potential_scale += particles.mass[k] * params.gravity.norm() * particles.radius[k];
    return;
  }
  // The walls' power as the force loop summed it, block by block (static walls do none), and what
  // holds the prescribed particles (their v and w are their own, before the motion and after it).
  double power = 0;
  if (walls_move_)
    for (double block : wall_power_) power += block;
  if (any_prescribed) power += prescribed_power(particles, block_force_.data(), block_torque_.data());
  const double work = power * dt;
  b.wall_work += work;
  b.wall_work_abs += std::abs(work);
  if (!energy_check_measures_now()) return;
  b.now = energy_before_motion();
  if (b.excess() > params.max_energy_gain * b.scale()) report_energy_gain();
}

void Simulation::report_energy_gain() const {
  const EnergyBalance& b = energy_;
  const Particles& p = particles;
  std::size_t top = 0;  // the particle with the most kinetic energy
  double top_e = -1, top_rot = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    double rot;
    const double e = kinetic_energy_of(p, k, rot);
    if (e > top_e) top = k, top_e = e, top_rot = rot;
  }
  std::ostringstream m;
  m << "energy created at step " << step << " (t = " << time << " s): since step " << b.step0
    << " the particles' kinetic + potential energy rose by " << b.now.total() - b.start.total() << " J, "
    << b.excess() << " J more than the walls' work (" << b.wall_work << " J) and the elastic energy then stored in the contacts (at most "
    << b.stored0 << " J) can supply (limit simulation.max_energy_gain = " << params.max_energy_gain << " x the energy scale "
    << b.scale() << " J); the most energetic particle is id " << p.id[top] << " (speed " << p.v[top].norm() << " m/s, spin "
    << p.w[top].norm() << " rad/s, " << (top_e > 0 ? 100 * top_rot / top_e : 0) << " % of its energy in rotation), with dt = " << dt
    << " s against the critical " << critical_time_step()
    << " s of docs/physics.md eq. P5";
  throw PhysicsError(m.str(), "lower the time step (frac), or check kn and kt (kt acts on the spin as well, which needs a shorter step)");
}

double Simulation::critical_time_step() const {
  double mmin = std::numeric_limits<double>::infinity();
  for (double m : particles.mass) mmin = std::min(mmin, m);
  // A fibre segment is a spring between two particles as a contact is (eq. P60).
  const double kmax = std::max(materials.max_stiffness(contact_scale()), fibres.empty() ? 0.0 : fibres.max_stiffness());
  if (!(kmax > 0) || !std::isfinite(mmin)) return std::numeric_limits<double>::infinity();
  return 2 * std::sqrt(mmin / (2 * kmax));  // eq. 2.48 (Hart et al.), without FRAC
}

double Simulation::dashpot_time_step() const {
  double mmin = std::numeric_limits<double>::infinity();
  for (double m : particles.mass) mmin = std::min(mmin, m);
  if (!std::isfinite(mmin)) return std::numeric_limits<double>::infinity();
  // c_n dt / (2 m*) grows as 1/sqrt(m*): the smallest m* is the lightest pair's, M_min / 2 (as eq.
  // 2.48's). The linear laws' dashpot reads kn (not the mendes law's tensile slope, which eq. 2.48 sees),
  // hertz's its slope at the largest overlap the run allows (eq. H5).
  const ContactScale scale = contact_scale();
  double c_max = 0;
  for (std::size_t a = 0; a < materials.size(); ++a)
    for (std::size_t b = 0; b < materials.size(); ++b) {
      const PairParams& p = materials.pair(a, b);
      c_max = std::max(c_max, with_normal_law(p.law, [&](auto law) {
                         using D = typename decltype(law)::Damping;
                         return D::largest_normal(p, 0.5 * mmin, std::is_same_v<D, HertzDamping> ? law.stiffness(p, scale) : p.kn);
                       }));
    }
  return c_max > 0 ? mmin / c_max : std::numeric_limits<double>::infinity();  // 2 m* / c_max
}

ContactScale Simulation::contact_scale() const {
  double r_max = 0;
  for (double r : particles.radius) r_max = std::max(r_max, r);
  return {r_max, params.max_overlap * r_max};  // the check stops a run past max_overlap x the smaller radius
}

double Simulation::kinetic_energy() const {
  const std::vector<std::size_t> by_id = particles.slots_by_id();  // a settle check stops on it: no bit may hang on storage order
  return mechanical_energy(particles, params.gravity, periodic, &by_id).kinetic;
}

// Reads the candidates directly (no compaction: the stress servo calls it every step). key_j (the
// wall index) is valid even before the first step after a restart, when slots are not: torques,
// which need the particle's slot, are for after a step.
std::vector<WallLoad> Simulation::wall_loads(bool torques) const {
  std::vector<WallLoad> load(walls.size());
  if (!torques) wall_loads_asked_ = true;  // the next force loops keep the copies while asked each step
  if (wall_forces_current_ && !torques) {  // the force loop's copies, in key order: the same sums
    for (const WallForce& w : wall_forces_) {
      if (!w.active) continue;
      WallLoad& l = load[w.wall];
      l.force += -w.force;
      ++l.contacts;
    }
    return load;
  }
  for (std::size_t r = 0; r < walls_.size(); ++r) {  // in key order: the same bits for any storage order
    const int k = key_rank_to_position(wall_by_key_, r);
    if (!walls_.active[k]) continue;
    WallLoad& l = load[walls_.key_j[k]];
    const Vec3 f = -walls_.force(k);
    l.force += f;
    ++l.contacts;
    if (torques) l.torque += closest_point(wall_geometry_[walls_.slot_j[k]], particles.x[walls_.slot_i[k]]).cross(f);
  }
  return load;
}

}  // namespace dem
