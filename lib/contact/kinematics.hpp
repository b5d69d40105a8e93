#pragma once
// What a contact law sees of one contact (its kinematics) and what it gives back (its force), for
// one contact with Eigen's vectors or over a lane type (simd/lanes.hpp).
#include "core/types.hpp"
#include "simd/lanes.hpp"

namespace dem {

// Relative kinematics of one contact, as seen from particle i (SPEC §5).
struct ContactKinematics {
  Vec3 n;          // unit normal from i to j (eq. 2.11 direction)
  double overlap;  // u_n > 0 in compression (eq. 2.11 / 2.17)
  Vec3 v_rel;      // v_j - v_i at the centres (wall: wall velocity - v_i)
  Vec3 w_arm;      // a_j w_j + a_i w_i (wall: a_i w_i), for eq. 2.12
  double m_eff;    // m_i m_j / (m_i + m_j), wall: m_i
  double r_eff;    // R* = a_i a_j / (a_i + a_j), wall: a_i (a law that needs it: hertz)
  // w_i - w_j (wall: w_i - the wall's spin): set only where the model has a rolling law, the one
  // reader (no default: the force loop's array of a chunk's kinematics would zero it for every slot).
  Vec3 w_rel;
};

struct ContactForce {
  Vec3 on_i;        // total force on i [N]; j receives the opposite (eq. 2.31-2.32)
  Vec3 tangential;  // tangential part of on_i, for the torques of eq. 2.33-2.34
  Vec3 couple = Vec3::Zero();  // rolling resistance: a torque on i [N m], on j the opposite (eq. R1)
  // The normal force f_n (repulsive > 0: on_i = -f_n n + tangential) and its elastic part f_el at
  // the overlap with the bond as the law left it: the energy ledger's dashpot work (eq. P33).
  double normal = 0, elastic = 0;
};

// While the energy log is on (sim/energy_ledger.hpp): what the law leaves of a pair contact for the
// ledger's work (docs/physics.md eq. P33-P34), so that the pass after the motion need not take its
// geometry and law again: only the velocities of the step are left to it. On i; on j the opposite.
struct ContactWork {
  Vec3 damping;     // the normal force beyond the elastic one, (f_n - f_el) n (eq. P33)
  Vec3 tangential;  // the tangential force (eq. P34)
};

// The law, written once over a lane type L (simd/lanes.hpp): one contact (L = double, from the
// plain loops, contact_law.hpp) or four (L = Lanes4, forces/pair_law_four_wide.hpp). `P` holds the pair
// constants by PairParams' names, as doubles or as lanes; `M` is L's mask type.
template <class L>
struct LaneKinematics {
  lanes::Triple<L> n;  // as ContactKinematics
  L overlap;
  lanes::Triple<L> v_rel, w_arm;
  L m_eff;
  L r_eff;
  lanes::Triple<L> w_rel{};  // as ContactKinematics
};
// The contact radius of elastic spheres, a = sqrt(R* u) (0 apart: u <= 0), docs/contact-laws.md
// eq. H1, H6, H8: written once, so that the Hertz force, its dashpot and Mindlin's stiffness and
// dashpot of one contact are the same expression, which the compiler computes once.
template <class L>
[[gnu::always_inline]] inline L contact_radius(const L& u, const L& r_eff) {
  return lanes::root(r_eff * lanes::only_where(lanes::less(L(0.0), u), u));
}
template <class L>
[[gnu::always_inline]] inline L contact_radius(const LaneKinematics<L>& c) {
  return contact_radius(c.overlap, c.r_eff);
}
// sqrt(m* a): the root both dashpots of Hertz-Mindlin take (eq. H6, H10), one expression for both.
template <class L>
[[gnu::always_inline]] inline L root_mass_radius(const LaneKinematics<L>& c, const L& a) {
  return lanes::root(c.m_eff * a);
}

template <class L>
struct LaneForce {
  lanes::Triple<L> on_i, tangential, couple;  // as ContactForce
  L normal, elastic;                          // as ContactForce (compiled away where unread)
};

}  // namespace dem
