#pragma once
// Materials and the contact parameters of each material pair (SPEC §6, "Mixing rules").
#include <optional>
#include <string>
#include <vector>

#include "contact/pair_params.hpp"

namespace dem {

struct Material {
  std::string name;
  double density = 2500;        // [kg/m^3]
  double kn = 1e5;              // normal stiffness [N/m]
  double kt = 1e5;              // tangential stiffness [N/m]
  double friction_angle = 30;   // [degrees]
  double restitution = 0.5;     // normal restitution eta_n, (0, 1]
  double restitution_t = 0.5;   // tangential restitution eta_t, (0, 1]
  NormalLaw law = NormalLaw::Cundall;
  double tensile_strength = 0;  // F [N], bonded contacts (liu, mendes)
  double cohesion = 0;          // C [N], bonded contacts (failure surface, fig. 2.13)
  double epsilon = 1e-4;        // mendes law shape parameter, (0, 1)
  bool no_viscous_attraction = false;  // clip the total normal force of unbonded contacts at zero
};

// How a parameter of two unlike materials is combined. Defaults follow SPEC §6.
enum class MixRule { Harmonic, Min, Max, Mean };

struct MixingRules {
  MixRule stiffness = MixRule::Harmonic;  // springs in series: harmonic mean 2 k1 k2 / (k1 + k2)
  MixRule friction = MixRule::Min;
  MixRule restitution = MixRule::Min;
  MixRule strength = MixRule::Min;        // tensile strength F, cohesion C, epsilon
};

// Explicit parameters for one material pair, overriding the mixing rules ([[pair]] in a scene).
struct PairOverride {
  int a = 0, b = 0;
  std::optional<NormalLaw> law;
  std::optional<double> kn, kt, friction_angle, restitution, restitution_t, tensile_strength, cohesion, epsilon;
  std::optional<bool> no_viscous_attraction;
};

double mix(MixRule rule, double a, double b);

class MaterialTable {
 public:
  MaterialTable() = default;
  MaterialTable(std::vector<Material> materials, MixingRules rules, const std::vector<PairOverride>& overrides = {});

  const std::vector<Material>& materials() const { return materials_; }
  const MixingRules& rules() const { return rules_; }
  std::size_t size() const { return materials_.size(); }
  const PairParams& pair(int a, int b) const { return pairs_[a * materials_.size() + b]; }
  int index_of(const std::string& name) const;  // -1 if absent
  double max_stiffness() const;                 // K_max of eq. 2.48 (incl. the mendes tensile slope)
  double max_break_separation() const;          // how far apart a bonded pair can still hold
  // The law all pairs share, or nullopt when the scene mixes laws.
  std::optional<NormalLaw> common_law() const;

 private:
  std::vector<Material> materials_;
  MixingRules rules_;
  std::vector<PairParams> pairs_;
};

}  // namespace dem
