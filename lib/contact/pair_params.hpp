#pragma once
// The contact constants of one material pair, derived once from the materials (state/materials.hpp)
// and read by the contact law (contact_law.hpp) for every contact of that pair.
namespace dem {

// Elastic normal law of a material pair (SPEC §6), a code per entry of the table in
// model_table.hpp (checkpoints store it): `cundall` has no tension; `liu` (eq. 2.21) and
// `mendes` (eq. 2.22-2.25) carry tension on bonded contacts only; `hertz` (docs/contact-laws.md
// eq. H1) grows as u^(3/2).
enum class NormalLaw { Cundall, Liu, Mendes, Hertz };

// Tangential law of a material pair, a code per entry of TangentialLaws (model_table.hpp):
// `coulomb`, a linear spring kt (eq. 2.13-2.16); `mindlin`, a spring whose stiffness grows with the
// contact radius (docs/contact-laws.md eq. H8).
enum class TangentialLaw { Coulomb, Mindlin };

// Rolling resistance of a material pair, a code per entry of RollingLaws (model_table.hpp): none,
// `cdt` (a constant couple) or `epsd2` (an elastic-plastic rotational spring), docs/contact-laws.md
// eq. R1-R4.
enum class RollingLaw { None, ConstantTorque, ElasticPlastic };

// Contact constants of one material pair, derived once (STYLE: a law's constants are precomputed).
struct PairParams {
  NormalLaw law = NormalLaw::Cundall;
  TangentialLaw tangential = TangentialLaw::Coulomb;
  RollingLaw rolling = RollingLaw::None;
  double kn = 0, kt = 0;
  double mu = 0;        // tan(friction angle)
  double gamma_n = 0;   // damping ratio from restitution, eq. 2.29
  double gamma_t = 0;
  // Dashpots c = damping x sqrt(m*) (eq. 2.28): damping_n = 2 gamma_n sqrt(kn); tangential with the
  // effective mass 2/7 m* of the contact point (contact/tangential.hpp): 2 gamma_t sqrt(2/7 kt).
  double damping_n = 0, damping_t = 0;
  double tensile_strength = 0;  // F [N]
  double cohesion = 0;          // C [N]
  bool no_viscous_attraction = false;
  bool explicit_dashpot = false;  // eq. D7 (LIGGGHTS's and LAMMPS's form) in place of D1-D6
  // mendes law (eq. 2.23-2.24 with SPEC's signs): T(s) = kn [D (1 - exp(-A s)) - s] for s < s0.
  bool mendes_tension = false;  // false for epsilon >= 1/e: no tension at all
  double mendes_D = 0, mendes_A = 0;
  double break_separation = 0;  // separation s at which a bond breaks: F/kn (liu), s0 (mendes), 0
  double hertz_modulus = 0;     // 4/3 E* [Pa] (hertz, eq. H1-H2)
  double hertz_damping = 0;     // 2 zeta sqrt(3/2 hertz_modulus) (hertz, eq. H6)
  double mindlin_modulus = 0;   // 8 G* [Pa] (mindlin, eq. H8-H9)
  double mindlin_damping = 0;   // 2 zeta_t sqrt(2/7 mindlin_modulus) (mindlin, eq. H10)
  double rolling_friction = 0;  // mu_r (cdt, epsd2: eq. R2-R4)
};

// The sizes a stiffness bound (eq. 2.48) may depend on: a law whose slope grows with the overlap
// (hertz) is bounded where a run would stop.
struct ContactScale {
  double radius = 0;   // the largest effective radius R* [m] (a wall contact: the largest radius)
  double overlap = 0;  // the largest overlap [m] the run's overlap check lets pass
};

}  // namespace dem
