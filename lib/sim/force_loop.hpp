#pragma once
// The force loop: forces of every contact this step, one loop per law combination (STYLE 3),
// chosen once per step outside the loops so that a scene pays only for what it uses.
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "sim/block_times.hpp"
#include "sim/load_sum.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

class Simulation;

// What the force loop reads.
struct ForceLoopInput {
  const Particles& particles;
  const MaterialTable& materials;
  const std::vector<Wall>& walls;
  const std::vector<WallGeometry>& geometry;  // the walls now
  const std::vector<int>& wall_runs;  // where each particle's wall candidates start (+ the end)
  const std::vector<int>& wall_run_order;   // the runs by their particle's storage slot
  const std::vector<int>& wall_block_first; // per load block, its first run in wall_run_order (+ the end)
  const PeriodicBox& periodic;
  bool any_fixed;  // some particle is held in place (Particles::fixed)
  bool any_bonds;  // some contact is bonded (Simulation::has_bonds)
  double dt;
  bool keep_pair_results;  // SimParams::keep_pair_results
};

// Per storage slot, the loads the force loop adds as it goes (no per-contact result to read back):
// the pair contacts of a block of storage slots [b block, (b + 1) block) whose other particle lies
// in the same block or one of the `reach` blocks after it, added to both particles; then each
// particle's wall contacts. The order of the pair sums: blocks form tiles of `reach` blocks (so a
// block writes into its own tile and the next one only); the even tiles come first, then the odd
// ones, and each tile's blocks in order, each block's contacts in their stored order. No two tiles
// of a phase write the same block, and each tile is swept once, its particles and the next tile's
// staying in cache (reach + 1 phases of single blocks, the earlier order, swept the particles
// reach + 1 times a step: 10^6 spheres on a lattice, one thread, 17 % slower). Pair contacts
// between blocks farther apart are summed afterwards per particle (Simulation::integrate). Blocks,
// tiles and phases depend on the storage only, never on the thread count: the same bits for any
// count.
struct BlockLoads {
  long block;                     // storage slots per block
  long reach;                     // blocks after a block whose contacts with it are summed here
                                  // (at least 1)
  const std::vector<long>& first; // where each block's candidates start (+ the end): those whose
                                  // smaller slot lies in the block (stored so, place_by_storage)
  BlockTimes& times;              // per block: its time at the last step, by which the threads
                                  // share the blocks out
  std::vector<long>& done;        // per block: the epoch of the force loop that last summed it
  long epoch;                     // this force loop's: unlike any before it
  std::vector<LoadSum>& force;    // per slot: sum of those contact forces [N]
  std::vector<LoadSum>& torque;   // per slot: sum of a n x f_t, eq. 2.33-2.34 [N m]
  bool zeroed;                    // force and torque hold zeros already (the last integration
                                  // cleared them as it read them), else the loop zeroes them
};

// SimParams::load_reach 0 (automatic) for `particles` particles in blocks of `block` slots: about
// 1.2 layers of spheres of a cube of them (storage is sorted along z, then y, then x:
// Simulation::sort_storage), at least 6 and at most 48 blocks. So the contacts between layers lie
// within reach at any size (10^6 spheres on a lattice, one thread: 21.5 s against 25.3 s with a
// reach of 24 blocks, whose vertical contacts were summed in the integration); at 48 blocks of 256
// a tile and the next still fit in a core's cache (2 MB). At least 6: a bed wider than high holds
// more per layer than a cube (the settle of 10^4 settles into layers of about 1,000 spheres: with
// 4 blocks, 5 % slower on one thread and 4 % on two; 8 blocks: as 6 on one thread, slower on two,
// whose runs then share tiles; the chute and a lattice of 10^4 the same with 5, 8 or 12).
long automatic_load_reach(long particles, long block);

// Tests only: thread `thread` of the pair loop pauses `microseconds` before each of its blocks, so
// that a block summed out of its order (a missing wait) shows in the bits; thread -1: none.
void set_lagging_thread_for_tests(int thread, int microseconds);

// Which instantiation runs: "cundall" (also any law while no contact is bonded: without bonds
// liu and mendes act exactly as cundall), "liu", "mendes" or "mixed".
enum class ForceVariant { Cundall, Liu, Mendes, Mixed };
ForceVariant choose_force_variant(const Simulation& sim);
const char* variant_name(ForceVariant v);

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

// The mass of eq. 2.26's damping for a pair: m_i m_j / (m_i + m_j), or against a particle held in
// place (infinitely heavy, as in LAMMPS's fix freeze) the other's mass.
inline double effective_mass(double mass_i, double mass_j, bool fixed_i, bool fixed_j) {
  if (fixed_i) return mass_j;
  if (fixed_j) return mass_i;
  return mass_i * mass_j / (mass_i + mass_j);
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
// exactly where the force loop sees a contact. The arrays hold n entries each.
void counted_wall_touches(const Particles& p, const std::vector<WallGeometry>& geometry, const ContactList& wc, int first,
                          int n, Vec3* to_wall, std::uint8_t* touching, std::uint8_t* take, int* order);

// For every candidate of `pairs` and `walls`: decides whether it is a contact (`active`: touching,
// or holding by a bond), and if so fills .normal and .sum (of pair contacts summed in `loads`, only
// where in.keep_pair_results) and updates its history; a candidate that is no contact gets a zero
// .sum and loses its spring. Pair contacts within a block or between blocks at most loads.reach
// apart, and wall contacts, are also summed into `loads`. Returns the largest overlap relative to
// the smaller radius of its contact.
double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls,
                              BlockLoads& loads);

}  // namespace dem
