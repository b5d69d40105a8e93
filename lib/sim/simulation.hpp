#pragma once
// A Simulation only wires the components together: particles, materials, walls, contacts, the
// force loop and the integrator. Everything here is part of the checkpoint (io/checkpoint.hpp).
#include <cstdint>
#include <optional>
#include <vector>

#include "contact/contact_list.hpp"
#include "forces/fluid.hpp"
#include "forces/void_fraction.hpp"
#include "core/block_times.hpp"
#include "forces/fibres.hpp"
#include "forces/force_loop.hpp"
#include "sim/energy_audit.hpp"
#include "sim/energy_ledger.hpp"
#include "state/load_sum.hpp"
#include "search/neighbour_list.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

struct SimParams {
  Vec3 gravity = Vec3(0, 0, -9.81);  // [m/s^2]
  double alpha_r = 0;                // global translational damping [1/s], eq. 2.36
  double alpha_theta = 0;            // global rotational damping [1/s], eq. 2.37
  double max_overlap = 0.5;          // stop when an overlap exceeds this fraction of the smaller radius
  double max_energy_gain = 0.5;      // stop when energy is created beyond this fraction of the energy
                                     // scale (sim/energy_audit.hpp); 0 = no check
  double skin = 0;                   // neighbour-list skin [m]; 0 = 0.2 x mean radius at each search. Speed only:
                                     // the contacts found do not depend on it
  // Storage order: at a simulation's first step and every sort_every steps (at steps that are
  // multiples of it), samples of at least sort_min_particles are put in the order of a grid of
  // cells, so that neighbours sit close in memory. 0 = never. The pair lists follow the storage
  // order, so both the particle and the contact loops become local (bench/results/locality.md).
  // Speed only: each particle's loads are summed in an order of its own (its contacts' keys;
  // forces/force_loop.hpp ForceBlocks), so no storage order changes a bit.
  long sort_every = 1000;
  long sort_min_particles = 10000;
  // A step of fewer particles than this runs on one thread: on a small scene the parallel regions'
  // barriers cost more than more cores save (about 2,000 spheres on two cores,
  // bench/results/scaling.md "Small scenes"). 0 = every step on all threads. The tools set it
  // (run/setup.cpp); speed only: no thread count changes a bit.
  long parallel_min_particles = 0;
  // Blocks of storage slots (ForceBlocks): the unit of work a thread takes in the force loop and
  // the integration, small for fine shares. Speed only.
  long load_block = 256;
  // Whether each step keeps every pair contact's normal (pair_contacts()'s normal and
  // tangential(k); read by post/contact_forces.hpp). Off, contact_forces() refuses the step: a
  // run whose outputs compute the forces on a copy (contact_forces_at_state) or read only keys,
  // springs and bonds (checkpoints) saves the stores. Never changes a result.
  bool keep_pair_results = true;
  // The stage's fluid (forces/fluid.hpp; docs/physics.md "Fluid drag"): none by default. While on,
  // each particle's void fraction is computed at steps that are multiples of fluid.void_every
  // (and whenever the particles change in number) and kept in Particles::void_fraction, which
  // the checkpoint holds.
  FluidParams fluid;
};

// What the particles exert on one wall element this step.
struct WallLoad {
  Vec3 force = Vec3::Zero();   // [N]
  Vec3 torque = Vec3::Zero();  // about the origin of coordinates [N m] (wall_loads(true) only)
  int contacts = 0;
};

// Tests only: every step takes its motion apart from the force loop, as the energy check's
// measuring steps do (Simulation::advance), so that a test compares both ways of taking a step.
void set_motion_apart_for_tests(bool apart);

class Simulation {
 public:
  Particles particles;
  MaterialTable materials;
  std::vector<Wall> walls;
  PeriodicBox periodic;  // none by default; positions stay inside it (set_periodic)
  SimParams params;
  FibreSet fibres;  // tension-only fibres tied to particles (forces/fibres.hpp); none by default
  double time = 0;            // [s]
  double dt = 0;              // [s]
  std::int64_t step = 0;
  // The energy balance (sim/energy_ledger.hpp), kept each step while ledger.on (off by default).
  EnergyLedger ledger;
  // Particles appended at slots [first, size()) between steps (insertion): while ledger.on, their
  // kinetic and potential energy enter the balance as brought in (docs/physics.md eq. P45).
  void account_inserted(std::size_t first);

  // One explicit step: contacts and forces at x^n with v^{n-1/2} (compute_forces), then
  // eq. 2.38-2.47. Where nothing reads the state between the two (the energy check on most steps,
  // no energy ledger, no fibres), each block of particles moves within the force loop, as soon as
  // its loads are summed (ForceBlocks::motion): the same bits, one pass over the particles less.
  void advance();
  // The first half of a step, without the motion: the contacts at x^n and their forces from
  // v^{n-1/2} and the stored history, readable afterwards through pair_contacts() and
  // wall_contacts(). It moves the contact history on as the step does (the springs take this
  // step's increment), so a run calls advance(), never both; post-processing calls it on a copy
  // (post/contact_forces.hpp). The storage order is left as it is (a step may sort it first).
  void compute_forces();

  // The contacts (touching, or holding by a bond) of the last step, sorted by key: particle-particle
  // and particle-wall (key_j = wall index). Compacted from the candidate lists on demand (not in
  // the time loop); after set_contacts, the lists given.
  const ContactList& pair_contacts() const;
  const ContactList& wall_contacts() const;
  // How many there are, without compacting them.
  std::size_t pair_contact_count() const;
  std::size_t wall_contact_count() const;
  // Frees the compacted copies (compacted again on demand). A caller that needs them once in a
  // while (a checkpoint) calls this afterwards, so that a long run does not carry a second copy
  // of its contacts from one checkpoint to the next.
  void release_contact_views() const;
  // Replaces the contact history (checkpoint read, a new scene, new particles): lists sorted by
  // key, slots found again at the next step.
  void set_contacts(ContactList pairs, ContactList walls);
  // Removes the particles marked in `gone` (per storage slot) and their candidates where the
  // neighbour list is current (as after a step): the others keep their order, history and
  // candidates (a filtered list still holds every pair within reach of those left), so no search
  // follows. Returns false, changing nothing, where the list is not current.
  bool remove_from_lists(const std::vector<char>& gone);

  // Stage action `bond`: Φ = 1 for every particle contact present now (and wall contacts if asked),
  // a pair counting as present when its gap is below `gap` x the smaller radius (a wall contact:
  // x the sphere's radius); gap = 0: touching as the force loop sees it (overlap > 0). Returns how
  // many contacts were bonded.
  std::size_t bond_present_contacts(bool walls_too, double gap = 0);
  bool has_bonds() const { return has_bonds_; }
  long bonds() const { return bonds_; }  // bonded pair and wall contacts now (kept as the force loop breaks them)
  // Whether pair_contacts()'s normals and forces are those of the last step (SimParams::keep_pair_results).
  bool pair_results_kept() const { return pair_results_kept_; }

  // Periodic boundaries from now on (a box with no periodic axis: none). Every particle is brought
  // into the period, its image counting the periods crossed (of the new period, when it changes:
  // unwrapped positions are kept).
  void set_periodic(const PeriodicBox& box);
  // Particle k's position as if no periodic boundary had been crossed (x + image L) [m].
  Vec3 unwrapped_position(std::size_t k) const {
    return periodic.unwrapped(particles.x[k], particles.image[k]);
  }

  // Critical time step of eq. 2.48 (without FRAC): 2 sqrt(M_min / (2 K_max)). The dashpot
  // (contact/damping.hpp) is stable below it at any damping.
  double critical_time_step() const;
  // The dashpot's limit 2 m*/c_max, m* = M_min/2 the lightest pair's (c_max: the largest normal
  // coefficient there): beyond it, c dt / (2 m*) > 1 and the damped oscillator's discrete motion
  // alternates in sign each step where the exact one creeps back without rebound
  // (docs/contact-laws.md, "The dashpot in time"): a cap on the step, FRAC or not. Infinite
  // without damping.
  double dashpot_time_step() const;
  // The largest radius and overlap of this run's contacts, for a stiffness that grows with them.
  ContactScale contact_scale() const;

  std::int64_t neighbour_builds() const { return neighbours_.builds(); }
  int step_threads() const { return step_threads_; }  // the threads the last step ran on (parallel_min_particles)

  double kinetic_energy() const;  // translational + rotational [J], summed in id order
  // The energy balance of the unstable-run check since its reference step (the first step, or the
  // first after set_contacts or a change in the particle count); updated every
  // kEnergyCheckEvery steps while params.max_energy_gain > 0.
  const EnergyBalance& energy_balance() const { return energy_; }
  static constexpr int kEnergyCheckEvery = 10;
  // Force, contacts and (if `torques`, only after a step) torque about the origin (contact point x
  // force) per wall element this step.
  // Without torques, from copies the force loop keeps while wall_loads() is asked every step (a
  // servo's), else from the candidates: the same bits.
  std::vector<WallLoad> wall_loads(bool torques = false) const;
  bool wall_loads_from_copies() const { return wall_forces_current_; }  // what the next wall_loads() reads
  const std::vector<WallGeometry>& wall_geometry() const { return wall_geometry_; }
  // Particle slot k's net load of the last step or compute_forces() (contacts, walls and gravity) [N];
  // zero before the first.
  Vec3 net_force(std::size_t k) const { return k < block_force_.size() ? block_force_[k].v : Vec3::Zero(); }

 private:
  [[noreturn]] void report_overlap(double worst) const;
  void audit_energy(bool any_prescribed);
  [[noreturn]] void report_energy_gain() const;
  void update_wall_geometry();
  void sort_storage();
  // The fluid's void fractions when due (SimParams::fluid) and fluid_grains_ when stale.
  void update_fluid_grains();
  void find_contacts();
  void count_bonds();
  // How a removal renumbered the particles and the pair candidates (remove_from_lists): each old
  // slot's new slot and each old candidate's new position, -1 where gone.
  struct Renumbering {
    const std::vector<int>& slot;
    const std::vector<int>& place;
  };
  // Each particle's pair candidates in key order (ForceBlocks) and the load blocks' runs of pair
  // and wall candidates; after a removal, each particle's list is its old one filtered.
  void index_contacts_per_particle(const Renumbering* removal = nullptr);
  void list_contacts_per_particle();
  void keep_contacts_per_particle(const Renumbering& removal);
  // compute_forces(), and with `motion` the step's motion too (ForceBlocks::motion).
  // With measure_energy (and `motion`), each block's mechanical energy before it moves, for the
  // energy check (energy_before_motion()).
  void compute_loads(const MotionStep* motion, bool measure_energy);
  // Whether the energy check runs (simulation.max_energy_gain), and whether this step is one where
  // it measures the particles' energy (before the motion).
  bool energy_check_on() const;
  bool energy_check_measures_now() const;
  bool energy_check_takes_reference() const;  // its first step, or the first after the particles changed
  // The particles' energy at x^n and v^{n-1/2} as the energy check sums it: the force loop's, block
  // by block, where it took it this step, else a pass over the same blocks (the same bits).
  MechanicalEnergy energy_before_motion() const;
  // The step's motion; with keep_state, the state before it kept for the energy ledger.
  MotionStep motion_step(bool any_fixed, bool keep_state);
  void integrate(bool any_fixed, bool keep_state);
  [[noreturn]] void report_not_finite(long slot) const;
  // The energy ledger's pass (sim/energy_ledger.cpp) after the motion, which kept x^n, v^{n-1/2}
  // and w^{n-1/2} (motion_step).
  void account_energy(bool any_fixed);
  // What the ledger's particle work reads (forces/step_work.hpp), the fluid's field `fluid` or null.
  StepWorkInput ledger_work_input(const FluidField* fluid, bool any_fixed) const;

  bool has_bonds_ = false;
  long bonds_ = 0;  // bond_count(), kept by count_bonds() and the bonds each force loop breaks
  std::vector<int> broken_pairs_, broken_walls_;  // the candidates whose bond the last force loop broke
  long bond_count() const;  // the sum of the pair and wall contacts' bonded flags (0: none bonded)
  bool pair_results_kept_ = true;
  EnergyBalance energy_;
  std::vector<MechanicalEnergy> check_energy_;  // per load block, its energy before the motion (ForceBlocks)
  bool check_energy_in_loop_ = false;  // whether the last force loop summed check_energy_
  NeighbourList neighbours_;
  // Every candidate pair of the neighbour list, with its history; `active` = a contact this step.
  ContactList pairs_, walls_;
  // Where pairs_ holds its entries in key order (contact/contact_list.hpp), found by sorting when
  // first needed after a rebuild that did not sort (outputs, error reports and the carry after a
  // re-sort of the storage need it; a run's steps do not).
  KeyOrder& pair_key_order() const;
  mutable KeyOrder pair_by_key_;
  mutable bool pair_by_key_current_ = true;
  KeyOrder pair_place_;   // working storage of place_by_storage and carry_history
  KeyOrder wall_by_key_;  // where walls_ holds its entries in key order (empty: in key order)
  // Per wall candidate its place in key order, and per place what wall_loads() reads (ForceLoopInput):
  // current from the force loop until the contacts are modified. Written only while something
  // reads them (a servo, every step): wall_loads() asked since the last loop; a loop after one that
  // did not write them clears them first (each keeps only the changes of its step).
  std::vector<int> wall_rank_;
  std::vector<WallForce> wall_forces_;
  bool wall_forces_current_ = false;
  bool wall_forces_written_ = false;       // by the last force loop
  mutable bool wall_loads_asked_ = false;  // since the last force loop
  void rank_wall_candidates();
  KeyOrder wall_place_;   // working storage of place_walls_by_storage and carry_history
  std::vector<int> place_count_;
  std::vector<int> carry_from_;  // working storage of carry_history
  mutable ContactList pair_view_, wall_view_;  // pair_contacts(), wall_contacts()
  mutable bool pair_view_current_ = false, wall_view_current_ = false;
  void contacts_modified();  // the views must be compacted again
  std::vector<WallGeometry> wall_geometry_;
  bool walls_move_ = false;  // some element of wall_geometry_ has a velocity or a spin
  // Per slot, its pair candidates as i then as j, each in key order (ForceBlocks::by_key); rebuilt
  // with the neighbour list.
  std::vector<int> by_key_start_, by_key_split_, by_key_, by_key_fill_, by_key_fill_j_;
  std::vector<long> block_first_;  // first pair candidate of each load block, then the end
  std::vector<long> block_needs_;  // per load block, the first block holding a candidate of its particles
  std::vector<long> needed_from_;  // per load block, the least block_needs_ of it and those after
  long indexed_block_ = 0;         // load_block of block_first_
  bool storage_sorted_ = false;    // sort_storage has run on this simulation's particles
  BlockTimes force_times_, integrate_times_;  // per load block, its time in each loop at the last step
  std::vector<long> block_done_;  // per load block, the epoch of the force loop that last computed it
  std::vector<std::uint8_t> touched_;  // per slot, the force loop's stamp where it last had a pair contact (ForceBlocks)
  long force_epoch_ = 0;          // force loops run (ForceBlocks::epoch)
  std::vector<LoadSum> block_force_, block_torque_;  // per slot, its net load this step (ForceBlocks)
  std::vector<double> wall_power_;  // per load block, the walls' power this step where the energy check needs it
  std::vector<int> wall_runs_;  // first wall candidate of each particle, then the end
  std::vector<int> wall_run_order_, wall_block_first_;  // ForceLoopInput's
  VoidFractionScratch void_scratch_;  // working storage of the fluid's void fractions
  // Per slot, FluidField::grain of its radius and void fraction (the force's constants), for the
  // fluid's viscosity and density in fluid_grains_for_; emptied when the void fractions are
  // recomputed or the storage is sorted, and rebuilt from them before the force loop.
  FluidGrains fluid_grains_;
  double fluid_grains_for_[2] = {0, 0};
  // While ledger.on: the state before the motion, kept on the steps whose pass after the motion
  // reads it (measuring, bonds, the motion apart: advance) (the bonds that broke this step, which
  // release their energy, are broken_pairs_ and broken_walls_).
  std::vector<Vec3> ledger_x_, ledger_v_, ledger_w_;
  std::vector<std::uint8_t> ledger_fibre_broken_;  // the fibre segments broken before the force loop
  std::vector<ContactWork> ledger_contact_work_;  // while ledger.on: what each pair contact's law left, per candidate
  bool ledger_work_zeros_ = false;  // every candidate of ledger_contact_work_ that is no contact holds zeros
                                    // (made and kept so by pass 1 while the log is on; lost at a rebuild)
  std::vector<ContactWork> ledger_wall_work_;     // while ledger.on: the same, per wall candidate
  ParticleWorkArrays ledger_particle_work_;  // while ledger.on, the motion apart: the force loop's contact sums, per slot
  StepWork ledger_work_;  // while ledger.on: the step's work the force loop and the motion added (ForceBlocks::step_work)
  bool ledger_particles_done_ = false;  // whether that includes the particles' (the motion ran in the loop)
  int step_threads_ = 0;                // step_threads()
  std::optional<ModelChoice> force_variant_;  // the force loop's this step (force_loop.hpp's ForceVariant)
};

}  // namespace dem
