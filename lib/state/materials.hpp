#pragma once
// Materials and the contact parameters of each material pair (SPEC §6, "Mixing rules").
#include <string>
#include <vector>

namespace dem {

enum class NormalLaw { Cundall };  // `liu` and `mendes` arrive with the "Contact physics" issue

struct Material {
  std::string name;
  double density = 2500;        // [kg/m^3]
  double kn = 1e5;              // normal stiffness [N/m]
  double kt = 1e5;              // tangential stiffness [N/m]
  double friction_angle = 30;   // [degrees]
  double restitution = 0.5;     // normal restitution eta_n, (0, 1]
  double restitution_t = 0.5;   // tangential restitution eta_t, (0, 1]
  NormalLaw law = NormalLaw::Cundall;
};

// How a parameter of two unlike materials is combined. Defaults follow SPEC §6.
enum class MixRule { Harmonic, Min, Max, Mean };

struct MixingRules {
  MixRule stiffness = MixRule::Harmonic;  // springs in series: harmonic mean 2 k1 k2 / (k1 + k2)
  MixRule friction = MixRule::Min;
  MixRule restitution = MixRule::Min;
};

// Contact constants of one material pair, derived once (STYLE: a law's constants are precomputed).
struct PairParams {
  double kn = 0, kt = 0;
  double mu = 0;        // tan(friction angle)
  double gamma_n = 0;   // damping ratio from restitution, eq. 2.29
  double gamma_t = 0;
};

double mix(MixRule rule, double a, double b);
double damping_ratio(double restitution);  // gamma = -ln(eta)/sqrt(pi^2 + ln^2 eta), eq. 2.29

class MaterialTable {
 public:
  MaterialTable() = default;
  MaterialTable(std::vector<Material> materials, MixingRules rules);

  const std::vector<Material>& materials() const { return materials_; }
  const MixingRules& rules() const { return rules_; }
  std::size_t size() const { return materials_.size(); }
  const PairParams& pair(int a, int b) const { return pairs_[a * materials_.size() + b]; }
  int index_of(const std::string& name) const;  // -1 if absent
  double max_stiffness() const;                 // K_max of eq. 2.48

 private:
  std::vector<Material> materials_;
  MixingRules rules_;
  std::vector<PairParams> pairs_;
};

}  // namespace dem
