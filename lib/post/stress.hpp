#pragma once
// Love-Weber stress (docs/physics.md eq. P26): per particle, and averaged over boxes (regions, slabs of a profile).
//
// Convention (docs/post.md): tension positive, compression negative (continuum mechanics), and
// the force index first, as SPEC §11 writes sigma = (1/V) sum_c f_c (x) l_c:
//   sigma_p = (1/V_p) sum_{c of p} f_c (x) (x_c - x_p),   i.e. sigma_ab = (1/V_p) sum f_a b_b,
// with f_c the force on p at contact c and x_c the contact point. The transpose, x_c (x) f_c, has
// the same symmetric part; the two differ only by the particle's unbalanced moment. Contact
// points: between two particles, the middle of the overlap on the line of centres
// (x_i + (a_i - a_j + d)/2 n), so that the two halves of a contact add up to its branch vector
// x_j - x_i; on a wall, the wall's closest point to the centre (eq. 2.4-2.5).
// The pressure p = -tr(sigma)/3 is positive in compression.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/types.hpp"
#include "forces/fibres.hpp"
#include "post/contact_forces.hpp"
#include "state/particles.hpp"

namespace dem {

using Mat3 = Eigen::Matrix3d;

// An axis-aligned box; the boundary counts as inside (as the scene's regions).
struct Box {
  Vec3 lo, hi;
  bool contains(const Vec3& x) const { return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all(); }
  double volume() const { return (hi - lo).prod(); }
};

// The bounding box of the spheres (centres +- radii).
Box sphere_box(const Particles& p);

inline double pressure_of(const Mat3& s) { return -s.trace() / 3; }
// Von Mises equivalent of the symmetric part's deviator: q = sqrt(3/2 s':s').
double deviatoric_q(const Mat3& s);

// sum_c f_c (x) (x_c - x_p) per particle [N m] (= V_p sigma_p) and the number of contacts.
struct ParticleStress {
  std::vector<Mat3> moment;
  std::vector<int> contacts;
};
// Per-particle gather over the contacts in a fixed order: the same bits for any thread count.
ParticleStress particle_stress(const Particles& p, const ContactForceSet& c);

// The fibres' segments as the stress sees them (docs/physics.md eq. P64): each segment between the
// particles a and b with tension T (fibres.tension, slack and broken ones left out) along e (tie a
// to tie b) acts as a contact carrying T e on a, with the branch vector l = x_b - x_a of the
// centres (nearest image across a periodic boundary). In segment order.
struct FibreBranches {
  std::vector<int> from, to;  // storage slots of a and b
  std::vector<Vec3> force;    // T e, the force on a [N]
  std::vector<Vec3> branch;   // l = x_b - x_a [m]
  std::size_t size() const { return from.size(); }
};
FibreBranches fibre_branches(const Particles& p, const PeriodicBox& box, const FibreSet& fibres);

// Adds the fibres' part (eq. P64): each of a segment's two particles takes half of T e (x) l.
// A serial loop in segment order.
void add_fibre_stress(const Particles& p, const PeriodicBox& box, const FibreSet& fibres, ParticleStress& s);

// sigma_p = moment / V_p [Pa], the contact part.
std::vector<Mat3> particle_stress_tensors(const Particles& p, const ParticleStress& s);

// Kinetic part per particle [Pa]: -m_p v'(x)v' / V_p with v' = v_p minus the mass-weighted mean
// velocity of all particles.
std::vector<Mat3> particle_kinetic_stress(const Particles& p);

// Averages over a box (a region, or one slab of a profile). A particle belongs wholly to the box
// that holds its centre; the box's own volume divides:
//   sigma_contact = (1/V) sum_{p in box} V_p sigma_p,
//   sigma_kinetic = -(1/V) sum_{p in box} m_p (v_p - vbar)(x)(v_p - vbar), vbar the box's
//   mass-weighted mean velocity.
struct BoxAverage {
  Box box;
  std::size_t count = 0;       // particles with their centre in the box
  double mass = 0;             // [kg]
  double solid_fraction = 0;   // sum V_p / V
  Vec3 mean_velocity = Vec3::Zero();  // mass-weighted [m/s]
  Mat3 contact = Mat3::Zero();        // [Pa]
  Mat3 kinetic = Mat3::Zero();        // [Pa]
  std::size_t displaced = 0;          // particles with a displacement (matched by id)
  Vec3 mean_displacement = Vec3::Constant(0);  // over those [m]; NaN when none
};

// `u` (optional): displacement per particle, NaN where not matched.
BoxAverage box_average(const Particles& p, const ParticleStress& s, const Box& box, const std::vector<Vec3>* u = nullptr);

// `bins` slabs of equal width along `axis` (0 x, 1 y, 2 z) across `region`; slab b holds the
// centres with lo + b h <= x < lo + (b+1) h (the last slab includes its upper face).
std::vector<BoxAverage> stress_profile(const Particles& p, const ParticleStress& s, const Box& region, int axis, int bins,
                                       const std::vector<Vec3>* u = nullptr);

}  // namespace dem
