#include "state/materials.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

double damping_ratio(double eta) {
  // eq. 2.29 (Tsuji et al.): realised restitution equals eta for the unclipped linear dashpot.
  const double l = std::log(eta);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

MaterialTable::MaterialTable(std::vector<Material> materials, MixingRules rules)
    : materials_(std::move(materials)), rules_(rules) {
  const std::size_t n = materials_.size();
  pairs_.resize(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const Material& A = materials_[a];
      const Material& B = materials_[b];
      PairParams& p = pairs_[a * n + b];
      p.kn = mix(rules_.stiffness, A.kn, B.kn);
      p.kt = mix(rules_.stiffness, A.kt, B.kt);
      const double deg = std::numbers::pi / 180.0;
      p.mu = std::tan(mix(rules_.friction, A.friction_angle, B.friction_angle) * deg);
      p.gamma_n = damping_ratio(mix(rules_.restitution, A.restitution, B.restitution));
      p.gamma_t = damping_ratio(mix(rules_.restitution, A.restitution_t, B.restitution_t));
    }
}

int MaterialTable::index_of(const std::string& name) const {
  for (std::size_t k = 0; k < materials_.size(); ++k)
    if (materials_[k].name == name) return static_cast<int>(k);
  return -1;
}

double MaterialTable::max_stiffness() const {
  double k = 0;
  for (const PairParams& p : pairs_) k = std::max({k, p.kn, p.kt});
  return k;
}

}  // namespace dem
