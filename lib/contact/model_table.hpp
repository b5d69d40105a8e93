#pragma once
// The one table of contact sub-models: the elastic normal laws and the tangential laws, each a
// list of models; the damping is the one each normal law names (Normal::Damping). A model's code
// is its place in its list (checkpoints store it); its keyword is its own. The parser, the materials (constants, eq. 2.48), the
// energy check, the servo and the force loop ask these tables, never a switch of their own.
// A new model: its type in its kind's file, one entry in its list below (a normal law also one
// value of NormalLaw, TangentialLaw or RollingLaw, contact/pair_params.hpp, in the same place), its tests,
// its keys in docs/scene.md.
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
#include "contact/rolling.hpp"
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
// Tangential laws, in the order of TangentialLaw's codes.
using TangentialLaws = ModelTable<CoulombSpring, MindlinSpring>;

// Rolling resistance laws, in the order of RollingLaw's codes.
using RollingLaws = ModelTable<NoRolling, ConstantTorque, ElasticPlasticRolling>;

constexpr int kNormalLaws = NormalLaws::size;  // codes 0 .. kNormalLaws - 1
constexpr int kTangentialLaws = TangentialLaws::size;
constexpr int kRollingLaws = RollingLaws::size;

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

template <class F>
decltype(auto) with_tangential_law(TangentialLaw law, F&& f) {
  return TangentialLaws::with(static_cast<int>(law), f);
}
// The tangential model of a pair.
template <class F>
decltype(auto) with_tangential_law(const PairParams& p, F&& f) {
  return with_tangential_law(p.tangential, f);
}
inline std::string_view tangential_law_name(TangentialLaw law) { return TangentialLaws::name(static_cast<int>(law)); }
inline std::optional<TangentialLaw> tangential_law_named(std::string_view keyword) {
  const std::optional<int> c = TangentialLaws::named(keyword);
  return c ? std::optional<TangentialLaw>(static_cast<TangentialLaw>(*c)) : std::nullopt;
}
inline std::vector<std::string> tangential_law_names() { return TangentialLaws::names(); }

template <class F>
decltype(auto) with_rolling_law(RollingLaw law, F&& f) {
  return RollingLaws::with(static_cast<int>(law), f);
}
inline std::string_view rolling_law_name(RollingLaw law) { return RollingLaws::name(static_cast<int>(law)); }
inline std::optional<RollingLaw> rolling_law_named(std::string_view keyword) {
  const std::optional<int> c = RollingLaws::named(keyword);
  return c ? std::optional<RollingLaw>(static_cast<RollingLaw>(*c)) : std::nullopt;
}
inline std::vector<std::string> rolling_law_names() { return RollingLaws::names(); }

// The damping of each contact's pair, per contact (MixedNormal's).
struct MixedDamping {
  static double coefficient(const PairParams& p, const LaneKinematics<double>& c) {
    return with_normal_law(p.law, [&](auto law) { return decltype(law)::Damping::coefficient(p, c); });
  }
  // The pair's dashpot over the step (damping.hpp's dashpot_force with its damping), or its
  // explicit form where the pair asks for it (ExplicitDashpot).
  static double force(const PairParams& p, const LaneKinematics<double>& c, double vn, double f_el, double dt, bool bonded,
                      double& mark) {
    return with_normal_law(p.law, [&](auto law) {
      using D = typename decltype(law)::Damping;
      return p.explicit_dashpot ? ExplicitDashpot<D>::force(p, c, vn, f_el, dt, bonded, mark)
                                : dashpot_force<D>(p, c, vn, f_el, dt, bonded, mark);
    });
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

// A scene whose material pairs use different tangential laws: the law of each contact's pair.
struct MixedTangential : TangentialSpring {
  static constexpr bool four_wide = false;
  static double dashpot(const PairParams& p, const LaneKinematics<double>& c) {
    return with_tangential_law(p, [&](auto law) { return decltype(law)::dashpot(p, c); });
  }
  static void force(const PairParams& p, const LaneKinematics<double>& c, double k_t, const lanes::Triple<double>& vt, double fn,
                    bool bonded, double dashpot, double dt, lanes::Triple<double>& spring, lanes::Triple<double>& ft) {
    with_tangential_law(p, [&](auto law) { decltype(law)::force(p, c, k_t, vt, fn, bonded, dashpot, dt, spring, ft); });
  }
  static double stiffness_at(const PairParams& p, const LaneKinematics<double>& c) {
    return with_tangential_law(p, [&](auto law) { return decltype(law)::stiffness_at(p, c); });
  }
};

// A scene whose material pairs use different rolling laws: the law of each contact's pair.
struct MixedRolling {
  static constexpr bool four_wide = false;
  static constexpr bool has_history = true;  // some pair's may
  static lanes::Triple<double> couple(const PairParams& p, const LaneKinematics<double>& c, double f_el, double k_t, double dt,
                                      lanes::Triple<double>& history) {
    return with_rolling_law(p.rolling, [&](auto law) { return decltype(law)::couple(p, c, f_el, k_t, dt, history); });
  }
};

// The sub-models a pair (or a whole scene) uses: what the force loop is compiled for.
struct ModelChoice {
  NormalLaw normal = NormalLaw::Cundall;
  TangentialLaw tangential = TangentialLaw::Coulomb;
  RollingLaw rolling = RollingLaw::None;
  bool explicit_dashpot = false;  // the normal law's damping in its explicit form (ExplicitDashpot)
  bool operator==(const ModelChoice&) const = default;
};

// Normal law N with its damping in the explicit form (docs/contact-laws.md eq. D7): what the force
// loop compiles for a scene whose pairs all ask for explicit_dashpot.
template <class N>
struct WithExplicitDashpot : N {
  using Damping = ExplicitDashpot<typename N::Damping>;
};

// The damping model of a pair: its normal law's.
template <class F>
decltype(auto) with_damping(const PairParams& p, F&& f) {
  return with_normal_law(p.law, [&](auto law) { return f(typename decltype(law)::Damping{}); });
}

// The scene keys a material with sub-models `m` reads: its normal law's, then its damping's, its
// tangential law's and its rolling law's, each once, in that order (a key's default_key comes
// before it).
inline std::vector<PropertyKey> property_keys(ModelChoice m) {
  std::vector<PropertyKey> keys;
  auto add = [&](const auto& list) {
    for (const PropertyKey& k : list)
      if (std::none_of(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == k.keyword; })) keys.push_back(k);
  };
  with_normal_law(m.normal, [&](auto law) { add(decltype(law)::keys), add(decltype(law)::Damping::keys); });
  with_tangential_law(m.tangential, [&](auto law) { add(decltype(law)::keys); });
  with_rolling_law(m.rolling, [&](auto law) { add(decltype(law)::keys); });
  return keys;
}
// Every key of every model, each once: what a checkpoint stores per material.
inline std::vector<PropertyKey> all_property_keys() {
  std::vector<PropertyKey> keys;
  for (int c = 0; c < kNormalLaws; ++c)
    for (int t = 0; t < kTangentialLaws; ++t)
      for (int r = 0; r < kRollingLaws; ++r)
        for (const PropertyKey& k : property_keys({static_cast<NormalLaw>(c), static_cast<TangentialLaw>(t), static_cast<RollingLaw>(r)}))
          if (std::none_of(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == k.keyword; })) keys.push_back(k);
  return keys;
}
// The laws that read a key, e.g. "law = \"liu\", law = \"mendes\"" (for messages).
inline std::string laws_reading(std::string_view keyword) {
  std::string list;
  const auto reads = [&](const auto& keys) {
    return std::any_of(std::begin(keys), std::end(keys), [&](const PropertyKey& k) { return k.keyword == keyword; });
  };
  const auto add = [&](std::string_view key, std::string_view name) {
    list += (list.empty() ? "" : ", ") + std::string(key) + " = \"" + std::string(name) + "\"";
  };
  for (int c = 0; c < kNormalLaws; ++c)
    with_normal_law(static_cast<NormalLaw>(c), [&](auto m) {
      if (reads(decltype(m)::keys) || reads(decltype(m)::Damping::keys)) add("law", decltype(m)::keyword);
    });
  for (int t = 0; t < kTangentialLaws; ++t)
    with_tangential_law(static_cast<TangentialLaw>(t), [&](auto m) {
      if (reads(decltype(m)::keys)) add("tangential", decltype(m)::keyword);
    });
  for (int r = 0; r < kRollingLaws; ++r)
    with_rolling_law(static_cast<RollingLaw>(r), [&](auto m) {
      if (reads(decltype(m)::keys)) add("rolling", decltype(m)::keyword);
    });
  return list;
}

// The constants of a material pair with sub-models `models` from its properties: each sub-model
// derives its own; the damping last, as it reads the normal stiffness.
inline PairParams derive_pair_params(ModelChoice models, const PairProperties& q) {
  PairParams p;
  p.law = models.normal;
  p.tangential = models.tangential;
  p.rolling = models.rolling;
  with_normal_law(p.law, [&](auto m) { m.derive(p, q); });
  with_tangential_law(p, [&](auto m) { m.derive(p, q); });
  with_rolling_law(p.rolling, [&](auto m) { m.derive(p, q); });
  with_damping(p, [&](auto m) { m.derive(p, q); });
  return p;
}

}  // namespace dem
