#pragma once
// The one table of contact sub-models: the elastic normal laws and the tangential laws, each a
// list of models; the damping is the one each normal law names (Normal::Damping). A model's code is its place in the list (checkpoints store the
// normal law's); its keyword is its own. The parser, the materials (constants, eq. 2.48), the
// energy check, the servo and the force loop ask these tables, never a switch of their own.
// A new model: its type in its kind's file, one entry in its list below (a normal law also one
// value of NormalLaw, contact/pair_params.hpp, in the same place), its tests, its keys in
// docs/scene.md.
#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "contact/damping.hpp"
#include "contact/normal_laws.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "contact/tangential.hpp"

namespace dem {

template <class... Models>
struct ModelTable {
  static constexpr int size = sizeof...(Models);

  // f(Model{}) for the model of `code` (the first for a code out of range: callers check codes).
  template <class F>
  static decltype(auto) with(int code, F&& f) {
    return with_from<0, Models...>(code, f);
  }
  static std::string_view name(int code) {
    return with(code, [](auto m) { return decltype(m)::keyword; });
  }
  // The code of a keyword, or none.
  static std::optional<int> named(std::string_view keyword) {
    for (int c = 0; c < size; ++c)
      if (name(c) == keyword) return c;
    return std::nullopt;
  }
  template <class M>
  static constexpr int code_of() {
    int code = 0, found = -1;
    ((std::is_same_v<M, Models> ? found = code : 0, ++code), ...);
    return found;
  }
  static std::vector<std::string> names() {
    std::vector<std::string> all;
    for (int c = 0; c < size; ++c) all.emplace_back(name(c));
    return all;
  }

 private:
  template <int Code, class M, class... Rest, class F>
  static decltype(auto) with_from(int code, F& f) {
    if constexpr (sizeof...(Rest) > 0)
      if (code != Code) return with_from<Code + 1, Rest...>(code, f);
    return f(M{});
  }
};

// Elastic normal laws, in the order of NormalLaw's codes.
using NormalLaws = ModelTable<CundallNormal, LiuNormal, MendesNormal, HertzNormal>;
using TangentialLaws = ModelTable<CoulombSpring>;

constexpr int kNormalLaws = NormalLaws::size;  // codes 0 .. kNormalLaws - 1

// f(Law{}) for the law of code `law`: f is called with an object of the law's type.
template <class F>
decltype(auto) with_normal_law(NormalLaw law, F&& f) {
  return NormalLaws::with(static_cast<int>(law), f);
}
inline std::string_view normal_law_name(NormalLaw law) { return NormalLaws::name(static_cast<int>(law)); }
inline std::optional<NormalLaw> normal_law_named(std::string_view keyword) {
  const std::optional<int> c = NormalLaws::named(keyword);
  return c ? std::optional<NormalLaw>(static_cast<NormalLaw>(*c)) : std::nullopt;
}
inline std::vector<std::string> normal_law_names() { return NormalLaws::names(); }
// The law `law` acts as while no contact is bonded.
inline NormalLaw law_without_bonds(NormalLaw law) {
  return with_normal_law(law, [](auto m) { return static_cast<NormalLaw>(NormalLaws::code_of<typename decltype(m)::WithoutBonds>()); });
}

// The damping of each contact's pair, per contact (MixedNormal's).
struct MixedDamping {
  static Dashpots<double> coefficients(const PairParams& p, const LaneKinematics<double>& c) {
    return with_normal_law(p.law, [&](auto law) { return decltype(law)::Damping::coefficients(p, c); });
  }
};

// A scene whose material pairs use different laws: the law of each contact's pair, per contact.
struct MixedNormal {
  static constexpr bool four_wide = false;
  using Damping = MixedDamping;
  static double elastic(const PairParams& p, double u, double r_eff, bool& bonded) {
    return with_normal_law(p.law, [&](auto law) { return decltype(law)::elastic(p, u, r_eff, bonded); });
  }
};

// The damping model of a pair: its normal law's.
template <class F>
decltype(auto) with_damping(const PairParams& p, F&& f) {
  return with_normal_law(p.law, [&](auto law) { return f(typename decltype(law)::Damping{}); });
}

// The scene keys a material with normal law `law` reads: its law's, then its damping's and its
// tangential law's, each once, in that order (a key's default_key comes before it).
inline std::vector<PropertyKey> property_keys(NormalLaw law) {
  std::vector<PropertyKey> keys;
  auto add = [&](const auto& list) {
    for (const PropertyKey& k : list)
      if (std::none_of(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == k.keyword; })) keys.push_back(k);
  };
  with_normal_law(law, [&](auto m) { add(decltype(m)::keys), add(decltype(m)::Damping::keys); });
  TangentialLaws::with(0, [&](auto m) { add(decltype(m)::keys); });
  return keys;
}
// Every key of every model, each once: what a checkpoint stores per material.
inline std::vector<PropertyKey> all_property_keys() {
  std::vector<PropertyKey> keys;
  for (int c = 0; c < kNormalLaws; ++c)
    for (const PropertyKey& k : property_keys(static_cast<NormalLaw>(c)))
      if (std::none_of(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == k.keyword; })) keys.push_back(k);
  return keys;
}
// The normal laws that read a key, e.g. "liu, mendes" (for messages).
inline std::string laws_reading(std::string_view keyword) {
  std::string list;
  for (int c = 0; c < kNormalLaws; ++c)
    for (const PropertyKey& k : property_keys(static_cast<NormalLaw>(c)))
      if (k.keyword == keyword) list += (list.empty() ? "" : ", ") + std::string(NormalLaws::name(c));
  return list;
}

// The constants of a material pair with normal law `law` from its properties: each sub-model
// derives its own; the damping last, as it reads the stiffnesses.
inline PairParams derive_pair_params(NormalLaw law, const PairProperties& q) {
  PairParams p;
  p.law = law;
  with_normal_law(law, [&](auto m) { m.derive(p, q); });
  TangentialLaws::with(0, [&](auto m) { m.derive(p, q); });
  with_damping(p, [&](auto m) { m.derive(p, q); });
  return p;
}

// The tangential model of a pair: one today, shared by every pair (a second one adds a code to
// PairParams).
template <class F>
decltype(auto) with_tangential_law(const PairParams& /*p*/, F&& f) {
  return TangentialLaws::with(0, f);
}

}  // namespace dem
