#pragma once
// The contact models of the peer benchmarks (bench/run_peer_bench.sh): the scenes' own linear
// spring-dashpot, or Hertz-Mindlin as LIGGGHTS's `pair gran model hertz tangential history`
// (docs/contact-laws.md eq. H1-H10), alone or with EPSD2 rolling resistance (`rolling_friction
// epsd2`, eq. R3-R4). bench/results/peers_hertz.md gives the peers' inputs for the same physics.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

#include "contact/damping.hpp"
#include "state/materials.hpp"

namespace dem::bench {

// The *Explicit models: the same with the explicit dashpot (docs/contact-laws.md eq. D7), the form
// the peers integrate.
enum class ContactModel { Linear, Hertz, HertzRolling, HertzExplicit, HertzRollingExplicit };

inline ContactModel contact_model_named(std::string_view name) {
  if (name == "linear") return ContactModel::Linear;
  if (name == "hertz") return ContactModel::Hertz;
  if (name == "hertz-rolling") return ContactModel::HertzRolling;
  if (name == "hertz-explicit") return ContactModel::HertzExplicit;
  if (name == "hertz-rolling-explicit") return ContactModel::HertzRollingExplicit;
  throw std::invalid_argument("contact model must be linear, hertz, hertz-rolling, hertz-explicit or hertz-rolling-explicit, not " +
                              std::string(name));
}
inline bool with_rolling(ContactModel m) { return m == ContactModel::HertzRolling || m == ContactModel::HertzRollingExplicit; }
inline bool with_explicit_dashpot(ContactModel m) { return m == ContactModel::HertzExplicit || m == ContactModel::HertzRollingExplicit; }

// The restitution of damping ratio gamma (the inverse of damping_ratio, eq. P14).
inline double restitution_of(double gamma) { return std::exp(-std::numbers::pi * gamma / std::sqrt(1 - gamma * gamma)); }

// What a Hertz bench material is made of (SI or LJ units, as the scene's).
struct HertzBead {
  double density, young_modulus, poisson_ratio, restitution, friction, rolling_friction;
};

// A Hertz-Mindlin material with LIGGGHTS's dashpots: normal c_n = 2 sqrt(5/6) gamma sqrt(m* S_n)
// is eq. H6-H7 as it stands; LIGGGHTS's tangential c_t = 2 sqrt(5/6) gamma sqrt(m* k_t) is our
// eq. H10 (with 2/7 m*) at gamma_t = sqrt(7/2) gamma. `mass_factor` scales both ratios by
// sqrt(m_peer* / m*) for a pair whose effective mass the peers take otherwise (a frozen sphere:
// m_peer* = m, ours m/2).
inline Material hertz_material(const std::string& name, const HertzBead& b, ContactModel model, double mass_factor = 1) {
  Material m;
  m.name = name;
  m.density = b.density;
  m.law = NormalLaw::Hertz;
  m.tangential = TangentialLaw::Mindlin;
  m.rolling = with_rolling(model) ? RollingLaw::ElasticPlastic : RollingLaw::None;
  m.rolling_friction = with_rolling(model) ? b.rolling_friction : 0;
  m.explicit_dashpot = with_explicit_dashpot(model);
  m.young_modulus = b.young_modulus;
  m.poisson_ratio = b.poisson_ratio;
  m.friction_angle = std::atan(b.friction) * 180 / std::numbers::pi;
  const double gamma = std::sqrt(mass_factor) * damping_ratio(b.restitution);
  m.restitution = restitution_of(gamma);
  m.restitution_t = restitution_of(std::sqrt(3.5) * gamma);
  return m;
}

}  // namespace dem::bench
