#include "state/materials.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact/model_table.hpp"

namespace dem {

double mix(MixRule rule, double a, double b) {
  switch (rule) {
    case MixRule::Harmonic: return (a + b) > 0 ? 2 * a * b / (a + b) : 0;
    case MixRule::Min: return std::min(a, b);
    case MixRule::Max: return std::max(a, b);
    case MixRule::Mean: return 0.5 * (a + b);
  }
  return a;
}

MaterialTable::MaterialTable(std::vector<Material> materials, MixingRules rules, const std::vector<PairOverride>& overrides)
    : materials_(std::move(materials)), rules_(rules) {
  const std::size_t n = materials_.size();
  pairs_.resize(n * n);
  const double deg = std::numbers::pi / 180.0;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const Material& A = materials_[a];
      const Material& B = materials_[b];
      const PairOverride* o = nullptr;
      for (const PairOverride& x : overrides)
        if ((x.a == static_cast<int>(a) && x.b == static_cast<int>(b)) || (x.a == static_cast<int>(b) && x.b == static_cast<int>(a))) o = &x;
      auto pick = [&](const std::optional<double> PairOverride::*field, MixRule rule, double va, double vb) {
        return (o && (o->*field)) ? *(o->*field) : mix(rule, va, vb);
      };
      PairParams& p = pairs_[a * n + b];
      // Unlike laws need an explicit [[pair]] (the parser checks); like laws carry over.
      p.law = (o && o->law) ? *o->law : A.law;
      p.kn = pick(&PairOverride::kn, rules_.stiffness, A.kn, B.kn);
      p.kt = pick(&PairOverride::kt, rules_.stiffness, A.kt, B.kt);
      p.mu = std::tan(pick(&PairOverride::friction_angle, rules_.friction, A.friction_angle, B.friction_angle) * deg);
      const double eta = pick(&PairOverride::restitution, rules_.restitution, A.restitution, B.restitution);
      const double eta_t = pick(&PairOverride::restitution_t, rules_.restitution, A.restitution_t, B.restitution_t);
      with_damping(p, [&](auto damping) { damping.derive(p, eta, eta_t); });
      p.tensile_strength = pick(&PairOverride::tensile_strength, rules_.strength, A.tensile_strength, B.tensile_strength);
      p.cohesion = pick(&PairOverride::cohesion, rules_.strength, A.cohesion, B.cohesion);
      p.no_viscous_attraction =
          (o && o->no_viscous_attraction) ? *o->no_viscous_attraction : (A.no_viscous_attraction || B.no_viscous_attraction);
      const double epsilon = pick(&PairOverride::epsilon, rules_.strength, A.epsilon, B.epsilon);
      with_normal_law(p.law, [&](auto law) { law.derive(p, epsilon); });
    }
}

int MaterialTable::index_of(const std::string& name) const {
  for (std::size_t k = 0; k < materials_.size(); ++k)
    if (materials_[k].name == name) return static_cast<int>(k);
  return -1;
}

double MaterialTable::max_stiffness() const {
  double k = 0;
  for (const PairParams& p : pairs_) {
    k = std::max({k, with_normal_law(p.law, [&](auto law) { return law.stiffness(p); }),
                  with_tangential_law(p, [&](auto law) { return law.stiffness(p); })});
  }
  return k;
}

double MaterialTable::max_break_separation() const {
  double s = 0;
  for (const PairParams& p : pairs_) s = std::max(s, p.break_separation);
  return s;
}

std::optional<NormalLaw> MaterialTable::common_law() const {
  if (pairs_.empty()) return NormalLaw::Cundall;
  for (const PairParams& p : pairs_)
    if (p.law != pairs_[0].law) return std::nullopt;
  return pairs_[0].law;
}

}  // namespace dem
