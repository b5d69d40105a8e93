#pragma once
// Pass 1 of the force loop: which pair candidates of a chunk are contacts (touching, or held by a
// bond). The others get no force and lose their history. Pass 2 (pair_law_four_wide.hpp) then runs the
// law on the contacts found, without an unpredictable branch, on the separations found here.
//
// Two versions give the same bits: a plain loop, and one that tests four candidates at once with
// AVX2 where the processor has it (simd/simd.hpp: the same operations in the same order per
// candidate, so the same separations and the same decisions). Pass 1 reads every candidate of
// the neighbour list, three or more per contact, and was a third of the chute's time.
#include <cstdint>

#include "contact/contact_list.hpp"
#include "core/types.hpp"
#include "forces/force_loop.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"

namespace dem {

// What pass 1 reads and writes, as bare arrays: the loop stores bytes (active, bonded), and a byte
// store may change any memory for the compiler, the vectors' own fields included; reading through
// the vectors it reloaded every array's address after each such store.
struct CandidateArrays {
  long count;  // candidates
  const Vec3* x;
  const double* radius;
  const int* slot_i;
  const int* slot_j;
  std::uint8_t* active;
  std::uint8_t* bonded;
  Vec3* spring;
  Vec3* rolling;
  double* dashpot;
  ContactSum* sum;
  ContactWork* work;  // ForceLoopInput::work: zeroed with the sum where a contact ends, or null
  bool work_unset;    // ForceLoopInput::work_unset: zero every candidate's work that is no contact

  CandidateArrays(const Particles& p, ContactList& pc, ContactWork* work_or_null, bool unset)
      : count(static_cast<long>(pc.size())), x(p.x.data()), radius(p.radius.data()), slot_i(pc.slot_i.data()),
        slot_j(pc.slot_j.data()), active(pc.active.data()), bonded(pc.bonded.data()), spring(pc.spring.data()),
        rolling(pc.rolling.data()), dashpot(pc.dashpot.data()), sum(pc.sum.data()), work(work_or_null),
        work_unset(work_or_null && unset) {}
};

// What pass 1 clears of a contact that ends: its history, its sum and (with the energy log) its
// work, so that every candidate that is no contact holds zeros (read as such by the sum pass).
inline void clear_lost_contact(const CandidateArrays& a, long k) {
  a.spring[k] = Vec3::Zero(), a.rolling[k] = Vec3::Zero(), a.dashpot[k] = 0, a.sum[k] = ContactSum();
  if (a.work) a.work[k] = {Vec3::Zero(), Vec3::Zero()};
}
// Candidate k is no contact now: what pass 1 clears of it.
inline void clear_no_contact(const CandidateArrays& a, long k, bool was) {
  if (was) clear_lost_contact(a, k);
  else if (a.work_unset) a.work[k] = {Vec3::Zero(), Vec3::Zero()};  // its history and sum are zeros already
}

// The contacts found in a chunk: candidate positions and separations x_j - x_i (nearest image),
// as separate arrays. Each array holds at least kFoundPadding entries more than the chunk has
// candidates (the four-wide version stores four at a time).
constexpr int kFoundPadding = 4;
struct FoundInChunk {
  int* contact;
  double* dx;
  double* dy;
  double* dz;
};

// Candidates [first, last): sets active (touching or bonded), clears the springs and sum of a contact
// lost, and stores each contact's position and separation in `found` in candidate order. Returns
// how many. (No candidate joins two fixed particles: the neighbour list leaves those out and is
// rebuilt when a fixed flag changes, which drops their history, bonds included.) `simd`: the
// four-wide version (simd_loops_on()).
// The arrays are taken by value: a copy that the loop's stores cannot change, so their addresses
// stay in registers.
template <bool Periodic>
int find_contacts(CandidateArrays a, const PeriodicBox& box, long first, long last, FoundInChunk found, bool simd);

// The plain loop, from candidate `first` on, appending to `found` from entry m (the four-wide
// version finishes a chunk's last one to three candidates with it).
template <bool Periodic>
inline int find_contacts_plain(const CandidateArrays& a, const PeriodicBox& box, long first, long last,
                               const FoundInChunk& found, int m) {
  for (long k = first; k < last; ++k) {
    const int i = a.slot_i[k], j = a.slot_j[k];
    const std::uint8_t was = a.active[k];
    const Vec3 d = separation<Periodic>(box, a.x[i], a.x[j]);
    // Bitwise, not ||: whether a candidate touches is a coin toss to the branch predictor.
    const std::uint8_t now = static_cast<std::uint8_t>(spheres_touch(d, a.radius[i], a.radius[j])) | a.bonded[k];
    a.active[k] = now;
    found.contact[m] = static_cast<int>(k);
    found.dx[m] = d.x(), found.dy[m] = d.y(), found.dz[m] = d.z();
    m += now;
    // A candidate that was no contact already holds zeros (ContactList): in a dense bed most
    // candidates are such, and rewriting their 72 bytes every step cost memory bandwidth.
    if (!now && (was || a.work_unset)) clear_no_contact(a, k, was);
  }
  return m;
}

}  // namespace dem
