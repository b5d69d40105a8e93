#pragma once
// The one table of elastic normal laws (contact/normal_laws.hpp): their codes (NormalLaw, stored in
// checkpoints), their scene keywords, and the call of a law's members for a pair's code. The
// parser, the materials (constants, eq. 2.48), the energy check and the force loop ask the table,
// never a switch of their own. A new law: one enum value in contact/pair_params.hpp and one case
// below.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/normal_laws.hpp"
#include "contact/pair_params.hpp"

namespace dem {

constexpr int kNormalLaws = 3;  // codes 0 .. kNormalLaws - 1

// f(Law{}) for the law of code `law`: f is called with an object of the law's type.
template <class F>
decltype(auto) with_normal_law(NormalLaw law, F&& f) {
  switch (law) {
    case NormalLaw::Liu: return f(LiuNormal{});
    case NormalLaw::Mendes: return f(MendesNormal{});
    case NormalLaw::Cundall: break;
  }
  return f(CundallNormal{});
}

inline std::string_view normal_law_name(NormalLaw law) {
  return with_normal_law(law, [](auto l) { return decltype(l)::keyword; });
}
// The law of a scene keyword, or none.
inline std::optional<NormalLaw> normal_law_named(std::string_view keyword) {
  for (int c = 0; c < kNormalLaws; ++c)
    if (normal_law_name(static_cast<NormalLaw>(c)) == keyword) return static_cast<NormalLaw>(c);
  return std::nullopt;
}
inline std::vector<std::string> normal_law_names() {
  std::vector<std::string> names;
  for (int c = 0; c < kNormalLaws; ++c) names.emplace_back(normal_law_name(static_cast<NormalLaw>(c)));
  return names;
}

// A scene whose material pairs use different laws: the law of each contact's pair, per contact.
struct MixedNormal {
  static constexpr bool four_wide = false;
  static double elastic(const PairParams& p, double u, bool& bonded) {
    return with_normal_law(p.law, [&](auto law) { return decltype(law)::elastic(p, u, bonded); });
  }
};

}  // namespace dem
