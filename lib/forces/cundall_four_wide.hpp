#pragma once
// Pass 2 of the force loop: the law on the contacts pass 1 found (find_contacts.hpp), and what
// each contact leaves behind: its sum (force on i and n x f_t), which each of its particles adds in
// the order of its contacts' keys (forces/force_loop.hpp), and its normal where kept.
//
// The plain version is three loops in force_loop.cpp (any law); a law written over lanes
// (contact/contact_law.hpp, simd/lanes.hpp; CundallNormal, the law of every scene without bonds)
// also runs four contacts at a time with AVX2 here: the same source, so the same bits.
#include <algorithm>
#include <cstdint>

#include "contact/contact_list.hpp"
#include "core/types.hpp"
#include "forces/find_contacts.hpp"
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
  Vec3* rolling;
  double* dashpot;
  Vec3* normal;
  ContactSum* sum;
  bool keep_normals;  // the normal of every contact (SimParams::keep_pair_results)

  PairLawArrays(const Particles& p, ContactList& pc, bool keep)
      : v(p.v.data()), w(p.w.data()), radius(p.radius.data()), mass(p.mass.data()), material(p.material.data()),
        fixed(p.fixed.data()), slot_i(pc.slot_i.data()), slot_j(pc.slot_j.data()), bonded(pc.bonded.data()),
        spring(pc.spring.data()), rolling(pc.rolling.data()), dashpot(pc.dashpot.data()), normal(pc.normal.data()), sum(pc.sum.data()), keep_normals(keep) {}
};

// What the law of contact k leaves: its sum (the force on i and n x f_t), and its normal where
// a.keep_normals.
inline void keep_pair_result(const PairLawArrays& a, long k, const Vec3& n, const Vec3& on_i, const Vec3& torque_per_radius) {
  if (a.keep_normals) a.normal[k] = n;
  a.sum[k] = {on_i, torque_per_radius};
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
double cundall_pair_law_simd(PairLawArrays a, const MaterialTable& materials, double dt, FoundInChunk found, int m, bool any_bonds);

}  // namespace dem
