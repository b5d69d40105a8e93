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

// R* = a_i a_j / (a_i + a_j), the pair's effective radius (docs/contact-laws.md eq. H3).
template <class L>
[[gnu::always_inline]] inline L effective_radius(const L& ri, const L& rj) {
  return (ri * rj) / (ri + rj);
}

// The kinematics of pair contact (i, j) (eq. 2.11-2.12, H3, and m* of eq. 2.26), written once over
// a lane type: the plain loops take one contact, the four-wide law four, with the same operations,
// so the same bits. In three parts written into `c`, so that the four-wide law gathers each part's
// values just before it and copies nothing (bench/results/design.md).
//
// The geometry, from d = x_j - x_i (the nearest image) and the radii: the unit normal n and the
// overlap (eq. 2.11).
template <class L>
[[gnu::always_inline]] inline void pair_geometry(const lanes::Triple<L>& d, const L& ri, const L& rj, LaneKinematics<L>& c) {
  using namespace lanes;
  const L dist = root(dot(d, d));
  c.n = d * (L(1.0) / dist);
  c.overlap = (ri + rj) - dist;
}
// The relative motion (eq. 2.12): v_rel, w_arm and, With_rolling, w_rel.
template <bool With_rolling, class L>
[[gnu::always_inline]] inline void pair_motion(const L& ri, const L& rj, const lanes::Triple<L>& vi, const lanes::Triple<L>& vj,
                                               const lanes::Triple<L>& wi, const lanes::Triple<L>& wj, LaneKinematics<L>& c) {
  c.v_rel = vj - vi;
  c.w_arm = rj * wj + ri * wi;
  if constexpr (With_rolling) c.w_rel = wi - wj;
}
// The effective mass and radius. With Fixed, a particle held in place (`held_i`, `held_j`) is
// infinitely heavy: m* is the other's mass (as LAMMPS's fix freeze).
template <bool Fixed, class L, class M>
[[gnu::always_inline]] inline void pair_inertia(const L& ri, const L& rj, const L& mi, const L& mj, const M& held_i, const M& held_j,
                                                LaneKinematics<L>& c) {
  c.m_eff = (mi * mj) / (mi + mj);
  if constexpr (Fixed) c.m_eff = lanes::select(held_i, mj, lanes::select(held_j, mi, c.m_eff));
  c.r_eff = effective_radius(ri, rj);  // a law that reads none: compiled away
}

// One contact's kinematics as Eigen's vectors (the plain loops, the tests) and over lanes.
template <bool With_rolling>
[[gnu::always_inline]] inline ContactKinematics contact_kinematics(const LaneKinematics<double>& k) {
  ContactKinematics c;  // w_rel set only With_rolling (ContactKinematics)
  c.n = lanes::vec3(k.n), c.overlap = k.overlap, c.v_rel = lanes::vec3(k.v_rel), c.w_arm = lanes::vec3(k.w_arm);
  c.m_eff = k.m_eff, c.r_eff = k.r_eff;
  if constexpr (With_rolling) c.w_rel = lanes::vec3(k.w_rel);
  return c;
}
template <bool With_rolling>
[[gnu::always_inline]] inline LaneKinematics<double> lane_kinematics(const ContactKinematics& c) {
  LaneKinematics<double> k{lanes::triple(c.n), c.overlap, lanes::triple(c.v_rel), lanes::triple(c.w_arm), c.m_eff, c.r_eff};
  if constexpr (With_rolling) k.w_rel = lanes::triple(c.w_rel);
  return k;
}
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
