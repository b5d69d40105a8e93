#pragma once
// The contact properties of a material as a scene gives them (SPEC §6), and the keys that name
// them. Each sub-model lists the keys it reads (its `keys`: keyword, range, unit, default, mixing
// rule), so that the scene parser, the mixing of unlike materials (state/materials.hpp) and the
// checkpoint all read one list; contact/model_table.hpp gathers them.
#include <algorithm>
#include <limits>
#include <string_view>

namespace dem {

// How a property of two unlike materials is combined. Defaults follow SPEC §6.
enum class MixRule { Harmonic, Min, Max, Mean };

struct MixingRules {
  MixRule stiffness = MixRule::Harmonic;  // springs in series: harmonic mean 2 k1 k2 / (k1 + k2)
  MixRule friction = MixRule::Min;
  MixRule restitution = MixRule::Min;
  MixRule strength = MixRule::Min;        // tensile strength F, cohesion C, epsilon
};

inline double mix(MixRule rule, double a, double b) {
  switch (rule) {
    case MixRule::Harmonic: return (a + b) > 0 ? 2 * a * b / (a + b) : 0;
    case MixRule::Min: return std::min(a, b);
    case MixRule::Max: return std::max(a, b);
    case MixRule::Mean: return 0.5 * (a + b);
  }
  return a;
}

// Every contact property a sub-model may read. A material holds them all; its models read theirs.
struct ContactProperties {
  double kn = 1e5;              // normal stiffness [N/m]
  double kt = 1e5;              // tangential stiffness [N/m]
  double friction_angle = 30;   // [degrees]
  double restitution = 0.5;     // normal restitution eta_n, (0, 1]
  double restitution_t = 0.5;   // tangential restitution eta_t, (0, 1]
  double tensile_strength = 0;  // F [N], bonded contacts (liu, mendes)
  double cohesion = 0;          // C [N], bonded contacts (failure surface, fig. 2.13)
  double epsilon = 1e-4;        // mendes law shape parameter, (0, 1)
  double young_modulus = 0;     // E [Pa] (hertz)
  double poisson_ratio = 0;     // nu (hertz)
  double rolling_friction = 0;  // mu_r (cdt, epsd2)
  bool no_viscous_attraction = false;  // clip the total normal force of unbonded contacts at zero
  bool explicit_dashpot = false;       // the dashpot at the step's velocity (docs/contact-laws.md eq. D7), not through the step
};

// What a material pair's constants derive from: each property mixed (by its key's rule, or the
// pair's own where a [[pair]] gives it), and both materials' own (for a law that combines them
// itself).
struct PairProperties {
  ContactProperties mixed, a, b;
};

// One scene key of a contact property.
struct PropertyKey {
  std::string_view keyword{};  // in [[material]] and [[pair]], and the checkpoint's /materials/<keyword>
  double ContactProperties::*number = nullptr;  // the property, or
  bool ContactProperties::*flag = nullptr;      // a true/false one
  double lo = 0, hi = 0;  // allowed range of a number, ends open where said
  bool lo_open = false, hi_open = false;
  std::string_view unit{};     // shown in messages with the range, e.g. "N/m"
  std::string_view si_unit{};  // the checkpoint's units attribute
  // The [mixing] rule for unlike materials (a flag: either's); none for a property each material
  // has, that its law combines itself (not given in a [[pair]]).
  MixRule MixingRules::*mixing = nullptr;
  // When a [[material]] omits it: required, or the value of an earlier key (default_key), or
  // default_value.
  bool required = false;
  std::string_view default_key{};
  double default_value = 0;
  // A flag checkpoints hold only since it was added (within their schema 4): a file without it was
  // written by a build that had it off, and reads so.
  bool absent_means_off = false;
};

// The elastic constants of a material, read by the laws of elastic spheres (hertz, mindlin), which
// combine the two materials' themselves (no mixing rule).
inline constexpr PropertyKey kYoungModulusKey = {.keyword = "young_modulus", .number = &ContactProperties::young_modulus, .lo = 0,
                                                 .hi = std::numeric_limits<double>::infinity(), .lo_open = true, .unit = "Pa",
                                                 .si_unit = "Pa", .required = true};
inline constexpr PropertyKey kPoissonRatioKey = {.keyword = "poisson_ratio", .number = &ContactProperties::poisson_ratio, .lo = -1,
                                                 .hi = 0.5, .lo_open = true, .hi_open = true, .unit = "(dimensionless)",
                                                 .si_unit = "1", .required = true};

}  // namespace dem
