#pragma once
// Pass 2 of the force loop: the law on the contacts pass 1 found (find_contacts.hpp), and what
// each contact leaves behind: its normal, its sum, and its loads on both particles.
//
// The plain version is three loops in force_loop.cpp (any law); a law written over lanes
// (contact/contact_law.hpp, simd/lanes.hpp; CundallNormal, the law of every scene without bonds)
// also runs four contacts at a time with AVX2 here: the same source, so the same bits.
#include <algorithm>
#include <cstdint>

#include "contact/contact_list.hpp"
#include "core/types.hpp"
#include "sim/find_contacts.hpp"
#include "sim/load_sum.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"

namespace dem {

// What pass 2 reads and writes, as bare arrays (see CandidateArrays).
struct PairLawArrays {
  const Vec3* v;
  const Vec3* w;
  const double* radius;
  const double* mass;
  const int* material;
  const std::uint8_t* fixed;
  const int* slot_i;
  const int* slot_j;
  std::uint8_t* bonded;
  Vec3* spring;
  Vec3* normal;
  ContactSum* sum;
  LoadSum* force;  // per slot: the loads summed in the force loop (BlockLoads)
  LoadSum* torque;
  bool keep_results;  // normal and sum of every contact (SimParams::keep_pair_results)

  PairLawArrays(const Particles& p, ContactList& pc, std::vector<LoadSum>& force_, std::vector<LoadSum>& torque_, bool keep)
      : v(p.v.data()), w(p.w.data()), radius(p.radius.data()), mass(p.mass.data()), material(p.material.data()),
        fixed(p.fixed.data()), slot_i(pc.slot_i.data()), slot_j(pc.slot_j.data()), bonded(pc.bonded.data()),
        spring(pc.spring.data()), normal(pc.normal.data()), sum(pc.sum.data()), force(force_.data()), torque(torque_.data()),
        keep_results(keep) {}
};

// What the law of contact k between slots i and j leaves: when both slots lie before `reach_end`
// (the smaller always lies in the block being summed), its loads on both particles, else its sum
// (the force on i and n x f_t), which integrate() adds; its normal and sum always where
// a.keep_results.
inline void keep_pair_result(const PairLawArrays& a, long k, int i, int j, const Vec3& n, const Vec3& on_i, const Vec3& torque_per_radius,
                             int reach_end) {
  const bool summed_here = std::max(i, j) < reach_end;
  if (a.keep_results) a.normal[k] = n;
  if (a.keep_results || !summed_here) a.sum[k] = {on_i, torque_per_radius};
  if (summed_here) {
    a.force[i].v += on_i;  // eq. 2.31-2.32
    a.force[j].v -= on_i;
    a.torque[i].v += a.radius[i] * torque_per_radius;  // eq. 2.33-2.34: a n x f_t for i and j alike
    a.torque[j].v += a.radius[j] * torque_per_radius;
  }
}

// overlap / radius where it may exceed `worst`, else 0: the division (one per contact) is done only
// near a new largest value. The margin keeps the result exact: whenever the quotient exceeds
// `worst`, the product test passes despite rounding, so the maximum is the same as dividing always.
inline double relative_overlap_if_larger(double overlap, double radius, double worst) {
  return overlap >= worst * radius * (1 - 1e-9) ? overlap / radius : 0.0;
}

// The Cundall law four contacts at a time on the m contacts `found` (whose arrays hold
// kFoundPadding entries more), as the plain loops would; returns the largest overlap relative to
// the smaller radius. Only where simd_loops_on(). (Arrays by value, as find_contacts.) any_bonds:
// some contact may be bonded (else every bonded flag is taken as 0, unread).
template <bool Fixed>
double cundall_pair_law_simd(PairLawArrays a, const MaterialTable& materials, double dt, FoundInChunk found, int m, int reach_end,
                             bool any_bonds);

}  // namespace dem
