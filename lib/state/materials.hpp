#pragma once
// Materials and the contact parameters of each material pair (SPEC §6, "Mixing rules").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/model_table.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"

namespace dem {

// A material: its name and density, its contact laws, and its contact properties (each read by
// the sub-model that owns its key, contact/model_table.hpp).
struct Material : ContactProperties {
  std::string name;
  double density = 2500;  // [kg/m^3]
  NormalLaw law = NormalLaw::Cundall;
  TangentialLaw tangential = TangentialLaw::Coulomb;
  RollingLaw rolling = RollingLaw::None;
  ModelChoice models() const { return {law, tangential, rolling}; }
};

// Explicit properties for one material pair, overriding the mixing rules ([[pair]] in a scene).
struct PairOverride {
  int a = 0, b = 0;
  std::optional<NormalLaw> law;
  std::optional<TangentialLaw> tangential;
  std::optional<RollingLaw> rolling;
  // The pair's laws: its own where given, else material `a`'s (unlike laws need a [[pair]]).
  ModelChoice models(const Material& a) const {
    return {law.value_or(a.law), tangential.value_or(a.tangential), rolling.value_or(a.rolling)};
  }
  ContactProperties values;         // those named in `given`
  std::vector<std::string> given;   // keywords of the properties given
  bool gives(std::string_view keyword) const;
  // Gives the property of `keyword` (a flag: value != 0); throws std::invalid_argument for a keyword
  // no model reads.
  void set(std::string_view keyword, double value);
};

class MaterialTable {
 public:
  MaterialTable() = default;
  MaterialTable(std::vector<Material> materials, MixingRules rules, const std::vector<PairOverride>& overrides = {});

  const std::vector<Material>& materials() const { return materials_; }
  const MixingRules& rules() const { return rules_; }
  const std::vector<PairOverride>& overrides() const { return overrides_; }
  std::size_t size() const { return materials_.size(); }
  const PairParams& pair(int a, int b) const { return pairs_[a * materials_.size() + b]; }
  int index_of(const std::string& name) const;  // -1 if absent
  // K_max of eq. 2.48 (incl. the mendes tensile slope; hertz's at the scale's radius and overlap).
  double max_stiffness(const ContactScale& scale) const;
  double max_break_separation() const;          // how far apart a bonded pair can still hold
  // The sub-models all pairs share, or nullopt when the scene mixes them; without `bonds`, the
  // normal law each acts as while no contact is bonded.
  std::optional<ModelChoice> common_models(bool bonds) const;

 private:
  std::vector<Material> materials_;
  MixingRules rules_;
  std::vector<PairOverride> overrides_;
  std::vector<PairParams> pairs_;
};

}  // namespace dem
