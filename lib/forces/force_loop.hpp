#pragma once
// The force loop: forces of every contact this step, one loop per law combination (STYLE 3),
// chosen once per step outside the loops so that a scene pays only for what it uses.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "contact/contact_list.hpp"
#include "contact/kinematics.hpp"
#include "core/block_times.hpp"
#include "forces/body_forces.hpp"
#include "forces/step_work.hpp"
#include "integrate/motion.hpp"
#include "state/load_sum.hpp"
#include "state/materials.hpp"
#include "state/mechanical_energy.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

class Simulation;

// A wall candidate as the walls' loads read it (Simulation::wall_loads), kept in key order: its
// wall, and this step whether it is a contact and its force on the particle.
struct WallForce {
  Vec3 force = Vec3::Zero();  // on the particle [N]
  std::int32_t wall = 0;      // the element (key_j)
  std::uint8_t active = 0;
};

// What the force loop reads.
struct ForceLoopInput {
  const Particles& particles;
  const MaterialTable& materials;
  const std::vector<WallGeometry>& geometry;  // the walls now
  const std::vector<int>& wall_runs;  // where each particle's wall candidates start (+ the end)
  const std::vector<int>& wall_run_order;   // the runs by their particle's storage slot
  const std::vector<int>& wall_block_first; // per load block, its first run in wall_run_order (+ the end)
  const PeriodicBox& periodic;
  bool any_fixed;  // some particle is fixed in place (Particles::fixed)
  bool any_bonds;  // some contact is bonded (Simulation::has_bonds)
  double dt;
  bool keep_pair_results;  // SimParams::keep_pair_results
  ContactWork* work = nullptr;       // per pair candidate: written by the law where the energy log is on;
                                     // zeros in every candidate that is no contact (pass 1 keeps them so)
  ContactWork* wall_work = nullptr;  // per wall candidate: the same
  bool work_unset = false;           // `work` holds anything after a rebuild: pass 1 zeroes every candidate's
                                     // that is no contact (in the parallel loop, not in a serial pass before)
  // Where given: per wall candidate its place in key order, and per place its WallForce, written
  // by the thread that takes the contact (in its cache), so that the walls' loads, which a servo
  // sums every step in key order, read them in order and not from the other core's cache.
  const int* wall_rank = nullptr;
  WallForce* wall_forces = nullptr;
};

// Each particle's net load, summed in the force loop in one order that depends on neither the
// storage order nor the thread count (docs/architecture.md): its weight, its pair contacts where
// it is i, then those where it is j (each run in the order of their keys), then its wall contacts
// in wall order, then the other body forces. Each pair contact's law
// runs once and leaves its sum (ContactList::sum) in the group of its smaller storage slot; a
// particle's pair contacts therefore all lie in the groups of its own block or earlier ones, and
// it is summed ("finished") right after its block's contacts, while they are in cache. Blocks
// whose particles have contacts in another thread's blocks are finished at the end of the
// thread's run, once those are done (`done`). The threads share the blocks out by their times at
// the last step.
struct ForceBlocks {
  long block;                       // storage slots per block: a thread's unit of work
  const std::vector<long>& first;   // where each block's candidates start (+ the end): those whose
                                    // smaller slot lies in the block (stored so, place_by_storage)
  const std::vector<long>& needs;   // per block: the first block holding a pair candidate of its
                                    // particles (their contacts are summed once it and those after
                                    // it are done)
  const std::vector<long>& needed_from;  // per block b: the smallest `needs` of blocks b and after
  const std::vector<int>& by_key_start;  // per slot: where its candidates start in by_key (+ the end)
  const std::vector<int>& by_key_split;  // per slot: where those in which it is j start in by_key
  const std::vector<int>& by_key;   // each slot's pair candidates k: those where it is i, then those
                                    // where it is j, each run in key order
  BlockTimes& times;                // per block: its time at the last step
  std::vector<long>& done;          // per block: the epoch of the force loop that last computed it
  std::vector<std::uint8_t>& touched;  // per slot: the low byte of the epoch of the force loop in which
                                       // it last had a pair contact (pass 1 stamps it; the sum skips
                                       // the others' lists; a stale stamp equal to this loop's only
                                       // makes a particle add its zeros)
  long epoch;                       // this force loop's: unlike any before it
  const BodyForces& body;           // added last
  bool simd;                        // simd_loops_on()
  std::vector<LoadSum>& force;      // per slot: the net force [N] (written, not added to)
  std::vector<LoadSum>& torque;     // per slot: the net torque [N m]
  ParticleWork work{};              // per slot, while the energy log is on (ForceLoopInput::work); written
                                    // only where the motion is not in the loop: else each block
                                    // keeps its own, which its motion reads (MotionWork)
  double* wall_power = nullptr;     // per block, where asked: Σ f · v_wall over its particles' wall
                                    // contacts (the walls' power, for the energy check) [W]
  // Within a step (Simulation::advance): each block's particles then move (integrate/motion.hpp)
  // as soon as their loads are summed, while those and the particles are in cache. No contact
  // still to compute reads them: a particle's contacts lie in its block or earlier ones, all done
  // by then. Null: the loads only (post-processing, or a step whose checks read the state first).
  const MotionStep* motion = nullptr;
  // While the energy log is on (with `work`): the step's work the loop adds, its wall contacts'
  // (add_wall_contact_work), with `motion` its particles' contacts' as they move (MotionWork) and,
  // where `particle_work` is given, the rest of their work once they have moved (add_particle_work).
  StepWork* step_work = nullptr;
  const StepWorkInput* particle_work = nullptr;
  // Where given (with `motion`): per block, its particles' mechanical energy just before they move
  // (state/mechanical_energy.hpp; x^n, v^{n-1/2}: the energy check's measuring steps).
  MechanicalEnergy* energy_before_motion = nullptr;
  long not_finite = -1;  // with motion: the last slot whose new state is not finite (move_particles)
  // Where given (empty): on return, the pair and the wall candidates whose bond the law broke, in
  // increasing order.
  std::vector<int>* broken_pairs = nullptr;
  std::vector<int>* broken_walls = nullptr;
};

// Tests only: thread `thread` of the force loop pauses `microseconds` before each block whose
// contacts it computes, so that a particle summed before the contacts it needs (a missing wait)
// shows in the bits; thread -1: none.
void set_lagging_thread_for_tests(int thread, int microseconds);

// Which instantiation of the force loop runs: the sub-models every pair shares
// (contact/model_table.hpp; while no contact is bonded, the normal law each acts as then: liu and
// mendes act exactly as cundall) where that combination is compiled (force_loop_units.hpp, kCompiled),
// or none: the laws chosen per contact ("mixed").
using ForceVariant = std::optional<ModelChoice>;
ForceVariant choose_force_variant(const MaterialTable& materials, bool any_bonds);
std::string variant_name(ForceVariant v);

// x_j - x_i, through the nearest image where boundaries are periodic. The force loop is compiled
// for both cases, so that a scene without periodic boundaries pays nothing for them.
template <bool Periodic>
inline Vec3 separation(const PeriodicBox& box, const Vec3& x_i, const Vec3& x_j) {
  if constexpr (Periodic) return box.nearest(x_j - x_i);
  else return x_j - x_i;
}
template <bool Periodic>
inline Vec3 separation(const Particles& p, const PeriodicBox& box, int i, int j) {
  return separation<Periodic>(box, p.x[i], p.x[j]);
}
inline Vec3 separation(const Particles& p, const PeriodicBox& box, int i, int j) {
  return box.any() ? separation<true>(p, box, i, j) : separation<false>(p, box, i, j);
}

// Whether a candidate touches now: the test that makes it a contact (with a bond, so does holding).
inline bool spheres_touch(const Vec3& separation, double radius_i, double radius_j) {
  const double r = radius_i + radius_j;
  return separation.squaredNorm() < r * r;
}
template <bool Periodic>
inline bool pair_touching(const Particles& p, const PeriodicBox& box, int i, int j) {
  return spheres_touch(separation<Periodic>(p, box, i, j), p.radius[i], p.radius[j]);
}
inline bool pair_touching(const Particles& p, const PeriodicBox& box, int i, int j) {
  return box.any() ? pair_touching<true>(p, box, i, j) : pair_touching<false>(p, box, i, j);
}
inline double wall_gap2(const Particles& p, const WallGeometry& g, int i, Vec3& to_wall) {
  to_wall = closest_point(g, p.x[i]) - p.x[i];
  return to_wall.squaredNorm();  // touching when < radius^2
}
// Whether particle i (reach^2 = r2) touches element g, `to_wall` its closest point - centre. Farther
// from the element's plane than the reach (with a margin far above round-off): no touch, whatever
// the closest point, and `to_wall` is left unset, unless the candidate was a contact at the last
// step (a new contact may take over its spring) or holds a bond: only those and the near ones pay
// for the closest point. (In a settling box most wall candidates are such near misses.)
inline bool wall_touches(const Particles& p, const WallGeometry& g, int i, double r2, bool was_active, bool bonded, Vec3& to_wall) {
  const double h = (p.x[i] - g.vertices[0]).dot(g.normal);
  if (!was_active && !bonded && h * h > r2 * (1 + 1e-6)) return false;
  return wall_gap2(p, g, i, to_wall) < r2;
}

// Which wall candidates of one particle are contacts. Where mesh elements meet, the same touch is
// seen by several elements (a face and its neighbour's edge, or two faces at their common edge):
// taken nearest first, a touch counts only if its contact point lies in front of the tangent plane
// of every touch already taken (c_k - c_j) . n_j > tol, n_j from c_j towards the centre. On a flat
// or convex surface the others lie in that plane or behind it, so the sphere feels one contact,
// as on a single plane; in a concave corner (a box's floor and side) both count.
// `to_wall[e]` = closest point - centre for candidate e of the run, `touching[e]` whether it
// touches; on return `take[e]` says which are contacts. `order` is working storage.
void select_wall_contacts(const Vec3* to_wall, const std::uint8_t* touching, int n, double radius, std::uint8_t* take,
                          int* order);

// The wall candidates [first, first + n) of one particle (a run of wall_runs): the vector to each
// element's closest point (`to_wall`; left unset for a candidate that neither touches nor was a
// contact or bond), whether it touches, and which touches count (`take`, by
// select_wall_contacts). Shared by the force loop and the bond action, so that a bond is made
// exactly where the force loop sees a contact. The arrays hold n entries each. `gap` (the bond
// action's tolerance, a fraction of the radius) counts a sphere apart by less than gap x radius as
// touching; the force loop passes 0.
void counted_wall_touches(const Particles& p, const std::vector<WallGeometry>& geometry, const ContactList& wc, int first,
                          int n, Vec3* to_wall, std::uint8_t* touching, std::uint8_t* take, int* order, double gap = 0);

// For every candidate of `pairs` and `walls`: decides whether it is a contact (`active`: touching,
// or holding by a bond), and if so fills .sum and .normal (of pair contacts only where
// in.keep_pair_results) and updates its history; a candidate that is no contact gets a zero .sum
// and loses its spring. Then each particle's net load into `blocks` (and, with blocks.motion, its
// motion). Returns the largest overlap relative to the smaller radius of its contact.
double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls,
                              ForceBlocks& blocks);

}  // namespace dem
