#include "state/materials.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact/model_table.hpp"

namespace dem {

bool PairOverride::gives(std::string_view keyword) const {
  return std::find(given.begin(), given.end(), keyword) != given.end();
}

void PairOverride::set(std::string_view keyword, double value) {
  for (const PropertyKey& k : all_property_keys()) {
    if (k.keyword != keyword) continue;
    if (k.flag) values.*k.flag = value != 0;
    else values.*k.number = value;
    if (!gives(keyword)) given.emplace_back(keyword);
    return;
  }
  throw std::invalid_argument("no contact model reads a property \"" + std::string(keyword) + "\"");
}

MaterialTable::MaterialTable(std::vector<Material> materials, MixingRules rules, const std::vector<PairOverride>& overrides)
    : materials_(std::move(materials)), rules_(rules), overrides_(overrides) {
  const std::size_t n = materials_.size();
  pairs_.resize(n * n);
  const std::vector<PropertyKey> keys = all_property_keys();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const Material& A = materials_[a];
      const Material& B = materials_[b];
      const PairOverride* o = nullptr;
      for (const PairOverride& x : overrides)
        if ((x.a == static_cast<int>(a) && x.b == static_cast<int>(b)) || (x.a == static_cast<int>(b) && x.b == static_cast<int>(a))) o = &x;
      // Each property: the pair's own where given, else the two materials' mixed by its rule.
      PairProperties q{A, A, B};
      for (const PropertyKey& k : keys) {
        const bool own = o && o->gives(k.keyword);
        if (k.flag) q.mixed.*k.flag = own ? o->values.*k.flag : (A.*k.flag || B.*k.flag);
        else if (own) q.mixed.*k.number = o->values.*k.number;
        else if (k.mixing) q.mixed.*k.number = mix(rules_.*k.mixing, A.*k.number, B.*k.number);
      }
      // Unlike laws need an explicit [[pair]] (the parser checks); like laws carry over.
      pairs_[a * n + b] = derive_pair_params(o ? o->models(A) : A.models(), q);
    }
}

int MaterialTable::index_of(const std::string& name) const {
  for (std::size_t k = 0; k < materials_.size(); ++k)
    if (materials_[k].name == name) return static_cast<int>(k);
  return -1;
}

double MaterialTable::max_stiffness(const ContactScale& scale) const {
  double k = 0;
  for (const PairParams& p : pairs_) {
    k = std::max({k, with_normal_law(p.law, [&](auto law) { return law.stiffness(p, scale); }),
                  with_tangential_law(p, [&](auto law) { return law.stiffness(p, scale); }),
                  with_rolling_law(p.rolling, [&](auto law) {
                    return law.stiffness(with_tangential_law(p, [&](auto t) { return t.stiffness(p, scale); }));
                  })});
  }
  return k;
}

double MaterialTable::max_break_separation() const {
  double s = 0;
  for (const PairParams& p : pairs_) s = std::max(s, p.break_separation);
  return s;
}

std::optional<ModelChoice> MaterialTable::common_models(bool bonds) const {
  if (pairs_.empty()) return ModelChoice{};
  const auto models = [&](const PairParams& p) {
    return ModelChoice{bonds ? p.law : law_without_bonds(p.law), p.tangential, p.rolling, p.explicit_dashpot};
  };
  for (const PairParams& p : pairs_)
    if (!(models(p) == models(pairs_[0]))) return std::nullopt;
  return models(pairs_[0]);
}

}  // namespace dem
