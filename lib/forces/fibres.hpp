#pragma once
// Fibres (docs/physics.md eq. P60-P64): straight segments tied to the particles they pass through,
// each stretch between two consecutive ties a tension-only spring that breaks for good at the
// fibre's strength. A force source added to the particles' net loads after the contacts and body
// forces, in one serial loop over the segments in a fixed order (the same bits for any thread
// count and storage order), with no allocation; a scene without fibres skips it on one test.
//
// A tie is fixed in its particle's body frame: its offset from the centre turns with the particle
// (rotate_ties, after each step's motion, by the angle w dt of the new angular velocity).
// Ties refer to particles by id; their storage slots are looked up again when the storage order
// changes (a sort, a removal): a tie whose particle is gone breaks the segments next to it.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "simd/lanes.hpp"
#include "state/load_sum.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

struct FibreSet {
  // Per fibre f: its ties are [first_tie[f], first_tie[f + 1]) (at least two), in order along it.
  std::vector<int> first_tie{0};
  std::vector<double> area;      // A = pi d^2 / 4 [m^2]
  std::vector<double> modulus;   // Young's modulus E [Pa]
  std::vector<double> strength;  // tensile strength sigma_t [Pa]
  // Per tie t.
  std::vector<Index> tie_id;     // the particle's id
  std::vector<Vec3> tie_offset;  // tie point - particle centre [m], turning with the particle
  // Per segment s (between ties tie_of[s] and tie_of[s] + 1, of fibre fibre_of[s]).
  std::vector<double> rest;             // L0 [m]: the length at placement
  std::vector<std::uint8_t> broken;     // 1: broken, for ever
  std::vector<double> tension;          // T of the last force computation [N] (output, not state)
  std::vector<int> tie_of, fibre_of;    // derived (index())
  std::vector<double> stiffness;        // derived: EA/L0 [N/m], so that a step divides by nothing
  std::vector<double> breaking;         // derived: sigma_t A [N], the tension at which it breaks (eq. P62)
  static constexpr int kGone = -1, kNotFound = -2;
  std::vector<int> tie_slot;            // derived: each tie's particle's storage slot, or kGone, kNotFound (not yet searched)
  std::size_t searches = 0;             // how often resolve() has searched the ids (tests)

  std::size_t fibres() const { return area.size(); }
  std::size_t ties() const { return tie_id.size(); }
  std::size_t segments() const { return rest.size(); }
  bool empty() const { return area.empty(); }

  // Appends one fibre: ties (particle id, offset from its centre) in order along it, one rest
  // length per segment, none broken.
  void add(const std::vector<std::pair<Index, Vec3>>& ties, const std::vector<double>& rest_lengths, double area_, double modulus_,
           double strength_);
  // Rebuilds tie_of, fibre_of, stiffness, breaking and sizes tension and tie_slot (after add or a checkpoint read).
  void index();
  // Finds each tie's slot again if any no longer holds its particle (checked every step, O(ties));
  // segments next to a tie whose particle is gone break. A particle gone stays gone (ids are never
  // used again), so its ties do not make it search again. Allocates only when it searches.
  void resolve(const Particles& p);
  // The present tie point of tie t [m] (slot resolved).
  Vec3 tie_point(const Particles& p, int t) const { return p.x[tie_slot[t]] + tie_offset[t]; }
  // The vector from tie a's point to tie b's (nearest image where boundaries are periodic).
  Vec3 span(const Particles& p, const PeriodicBox& box, int a, int b) const;
  // Elastic energy of the intact segments: sum EA/(2 L0) (L - L0)^2 for L > L0 [J].
  double elastic_energy(const Particles& p, const PeriodicBox& box) const;
  // Tensile strength of segment s as a force, sigma_t A [N].
  double break_force(int s) const { return breaking[s]; }
  std::size_t broken_count() const;
  // The stiffest intact segment's EA/L0 [N/m] (0 with none): it joins eq. P5's K_max.
  double max_stiffness() const;
};

// Eq. P60-P61: the tension [N] of a segment of stiffness k = EA/L0 (FibreSet::stiffness), rest
// length L0 and present length L: k (L - L0) when stretched, 0 when slack. Written once over a
// lane type L (simd/lanes.hpp: one segment, or four).
template <class L>
[[gnu::always_inline]] inline L segment_tension(const L& stiffness, const L& rest, const L& length) {
  const L stretch = length - rest;
  return lanes::only_where(lanes::less(L(0.0), stretch), stiffness * stretch);
}

// Each segment's tension into fibres.tension, as the force loop would find it at this state (0
// for a broken segment and for one beyond its strength), without breaking any: for outputs.
void compute_fibre_tensions(FibreSet& fibres, const Particles& p, const PeriodicBox& box);

// Eq. P60-P62: each intact segment's tension, set into fibres.tension; a segment whose tension
// would exceed sigma_t A breaks (tension 0 from this step on). The force T e (e the unit vector
// from tie a to tie b) acts on a's particle at its tie point, -T e on b's; each adds its force and
// its torque offset x force to the particle's net load, in segment order. Resolves the slots.
void add_fibre_forces(FibreSet& fibres, const Particles& p, const PeriodicBox& box, std::vector<LoadSum>& force,
                      std::vector<LoadSum>& torque);

// Turns every tie's offset by its particle's rotation over the step, the angle |w| dt about w
// (w the angular velocity just integrated, as the centre moves by v dt).
void rotate_ties(FibreSet& fibres, const Particles& p, double dt);

}  // namespace dem
