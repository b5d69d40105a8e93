#include "io/scene_parser.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>

#include "contact/model_table.hpp"
#include "core/error.hpp"
#include "generation/insertion.hpp"
#include "generation/size_distribution.hpp"
#include "io/file_seal.hpp"
#include "io/stl.hpp"
#include "walls/primitives.hpp"

namespace dem {

namespace {

// "a", "b", "c"
std::string quoted_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& a : names) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
  return list;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

// The plausibility warnings of the scene being parsed (parse_scene sets it): TableReader::warn adds
// to it from any nested reader.
thread_local std::vector<std::string>* warnings_out = nullptr;

// The ranges a granular scene has (docs/scene.md, "Warnings"). A value outside them is accepted
// with a warning that names the likely cause, almost always a unit.
constexpr double kDensityLo = 100, kDensityHi = 25000;       // kg/m^3: light polymers .. osmium (22,590)
constexpr double kRadiusHi = 1;                              // m: a particle's radius
constexpr double kExtentHi = 100;                            // m: generation box, a wall, a period
constexpr double kStiffnessLo = 1, kStiffnessHi = 1e12;      // N/m: kn, kt
constexpr double kModulusLo = 1e5, kModulusHi = 1.2e12;      // Pa: soft rubber .. diamond
constexpr double kGravityLo = 1, kGravityHi = 30;            // m/s^2 (or 0): the Moon's 1.62 .. Jupiter's 24.8
constexpr double kAmplitudeHi = 0.1;                         // m: a vibration's amplitude
constexpr double kVibrationHi = 100 * 9.81;                  // m/s^2: a vibration's peak acceleration, 100 g
constexpr double kFracHi = 0.2;                              // FRAC above it gives wrong results (README)

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string show(const toml::node& n) {
  std::ostringstream s;
  if (n.is_string()) s << '"' << *n.value<std::string>() << '"';
  else if (n.is_table()) s << "{...}";
  else if (n.is_array()) s << "[...]";
  else if (n.is_boolean()) s << (*n.value<bool>() ? "true" : "false");
  else if (n.is_integer()) s << *n.value<int64_t>();
  else if (n.is_floating_point()) s << *n.value<double>();
  else s << "(date/time)";
  return s.str();
}

const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date/time";
  }
}

// One TOML table being read: remembers which keys were used so that unknown keys are rejected,
// and formats every message as "file:line:col: where.key = value: problem".
class TableReader {
 public:
  TableReader(const toml::table& t, std::string file, std::string where)
      : t_(t), file_(std::move(file)), where_(std::move(where)) {}

  [[noreturn]] void fail_at(const toml::node* n, const std::string& key, const std::string& msg) const {
    std::ostringstream s;
    const toml::source_region& src = n ? n->source() : t_.source();
    s << file_ << ':' << src.begin.line << ':' << src.begin.column << ": " << name(key);
    if (n) s << " = " << show(*n);
    s << ": " << msg;
    throw InputError(s.str());
  }
  [[noreturn]] void fail(const std::string& key, const std::string& msg) const { fail_at(t_.get(key), key, msg); }
  // A plausibility warning, formatted as fail_at's message; kept in Scene::warnings.
  void warn_at(const toml::node* n, const std::string& key, const std::string& msg) const {
    if (!warnings_out) return;
    std::ostringstream s;
    const toml::source_region& src = n ? n->source() : t_.source();
    s << file_ << ':' << src.begin.line << ':' << src.begin.column << ": " << name(key);
    if (n) s << " = " << show(*n);
    s << ": " << msg;
    warnings_out->push_back(s.str());
  }
  void warn(const std::string& key, const std::string& msg) const { warn_at(t_.get(key), key, msg); }

  std::string name(const std::string& key) const { return where_.empty() ? key : where_ + "." + key; }
  bool has(const std::string& key) {
    used_.insert(key);
    return t_.contains(key);
  }
  const toml::node* node(const std::string& key) {
    used_.insert(key);
    return t_.get(key);
  }
  const toml::node& required(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) {
      std::ostringstream s;
      s << file_ << ':' << t_.source().begin.line << ": " << name(key) << " is missing (required)";
      throw InputError(s.str());
    }
    return *n;
  }

  // A number in [lo, hi] (open ends when lo_open / hi_open). `unit` is shown in messages.
  double number_of(const toml::node& n, const std::string& key, double lo, double hi, const char* unit,
                   bool lo_open = false, bool hi_open = false) const {
    if (!n.is_number()) fail_at(&n, key, std::string("expected a number [") + unit + "], got " + type_name(n));
    const double v = *n.value<double>();
    const bool below = lo_open ? !(v > lo) : !(v >= lo);
    const bool above = hi_open ? !(v < hi) : !(v <= hi);
    if (!std::isfinite(v) || below || above) {
      std::ostringstream s;
      s << "out of range: allowed " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open || std::isinf(hi) ? ")" : "]") << " " << unit;
      fail_at(&n, key, s.str());
    }
    return v;
  }
  // An interval (core/interval.hpp): seconds as a number, or a string with its unit, "400 steps" or
  // "0.01 s". 0 is allowed where `zero_ok` (it means off). `unit` is shown in messages.
  Interval interval_or(const std::string& key, Interval def, bool zero_ok, const char* unit) {
    const toml::node* n = node(key);
    if (!n) return def;
    if (n->is_number()) return seconds(number_of(*n, key, 0, std::numeric_limits<double>::infinity(), unit, !zero_ok));
    if (!n->is_string())
      fail_at(n, key, std::string("expected seconds (a number) or a string such as \"400 steps\" or \"0.01 s\", got ") + type_name(*n));
    std::string why;
    const std::optional<Interval> r = parse_interval(*n->value<std::string>(), Interval::Unit::Seconds, zero_ok, why);
    if (!r) fail_at(n, key, why);
    return *r;
  }
  double number(const std::string& key, double lo, double hi, const char* unit, bool lo_open = false, bool hi_open = false) {
    return number_of(required(key), key, lo, hi, unit, lo_open, hi_open);
  }
  double number_or(const std::string& key, double def, double lo, double hi, const char* unit, bool lo_open = false,
                   bool hi_open = false) {
    const toml::node* n = node(key);
    return n ? number_of(*n, key, lo, hi, unit, lo_open, hi_open) : def;
  }
  long integer_or(const std::string& key, long def, long lo, long hi) {
    const toml::node* n = node(key);
    if (!n) return def;
    if (!n->is_integer()) fail_at(n, key, std::string("expected an integer, got ") + type_name(*n));
    const long v = static_cast<long>(*n->value<int64_t>());
    if (v < lo || v > hi) fail_at(n, key, "out of range: allowed [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  long integer(const std::string& key, long lo, long hi) {
    required(key);
    return integer_or(key, 0, lo, hi);
  }
  bool boolean_or(const std::string& key, bool def) {
    const toml::node* n = node(key);
    if (!n) return def;
    if (!n->is_boolean()) fail_at(n, key, std::string("expected true or false, got ") + type_name(*n));
    return *n->value<bool>();
  }
  std::string string_of(const toml::node& n, const std::string& key) const {
    if (!n.is_string()) fail_at(&n, key, std::string("expected a string, got ") + type_name(n));
    return *n.value<std::string>();
  }
  std::string string(const std::string& key) { return string_of(required(key), key); }
  // A string from a fixed set of choices.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const std::string* def = nullptr) {
    const toml::node* n = node(key);
    if (!n && def) return *def;
    const std::string v = string_of(n ? *n : required(key), key);
    for (const std::string& a : allowed)
      if (a == v) return v;
    fail_at(n, key, "unknown value: allowed " + quoted_list(allowed));
  }
  Vec3 vec3_of(const toml::node& n, const std::string& key) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3) fail_at(&n, key, "expected an array of 3 numbers [x, y, z]");
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      const toml::node& e = *a->get(k);
      if (!e.is_number() || !std::isfinite(*e.value<double>())) fail_at(&n, key, "expected an array of 3 finite numbers [x, y, z]");
      v[k] = *e.value<double>();
    }
    return v;
  }
  Vec3 vec3(const std::string& key) { return vec3_of(required(key), key); }
  Vec3 vec3_or(const std::string& key, const Vec3& def) {
    const toml::node* n = node(key);
    return n ? vec3_of(*n, key) : def;
  }
  const toml::table* subtable(const std::string& key) {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail_at(n, key, std::string("expected a table, got ") + type_name(*n));
    return n->as_table();
  }
  // An array of tables ([[key]]); empty if absent.
  std::vector<const toml::table*> tables(const std::string& key) {
    std::vector<const toml::table*> out;
    const toml::node* n = node(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a) fail_at(n, key, std::string("expected an array of tables [[") + key + "]], got " + type_name(*n));
    for (const toml::node& e : *a) {
      if (!e.is_table()) fail_at(&e, key, "expected a table in [[" + key + "]]");
      out.push_back(e.as_table());
    }
    return out;
  }

  // Rejects every key that no reader asked for.
  void finish() const {
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      if (!used_.count(key)) {
        std::string list;
        for (const std::string& u : used_) list += (list.empty() ? "" : ", ") + u;
        fail_at(&v, key, "unknown key (allowed here: " + list + ")");
      }
    }
  }

  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  const toml::table& t_;
  std::string file_, where_;
  std::set<std::string> used_;
};

std::string indexed(const std::string& what, std::size_t k) { return what + "[" + std::to_string(k) + "]"; }

MixRule read_mix(TableReader& r, const std::string& key, MixRule def) {
  static const std::vector<std::string> names = {"harmonic", "min", "max", "mean"};
  const std::string defname = names[static_cast<int>(def)];
  const std::string v = r.choice(key, names, &defname);
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == v) return static_cast<MixRule>(k);
  return def;
}

// Index of the material called `name`, or -1.
int find_material(const std::vector<Material>& mats, const std::string& name) {
  for (std::size_t k = 0; k < mats.size(); ++k)
    if (mats[k].name == name) return static_cast<int>(k);
  return -1;
}

int material_ref(TableReader& r, const std::string& key, const std::vector<Material>& mats) {
  const toml::node& n = r.required(key);
  const std::string name = r.string_of(n, key);
  if (const int k = find_material(mats, name); k >= 0) return k;
  std::string list;
  for (const Material& m : mats) list += (list.empty() ? "" : ", ") + ("\"" + m.name + "\"");
  r.fail_at(&n, key, "no material of that name (defined: " + list + ")");
}

SettleSpec read_settle(TableReader& parent, const std::string& key) {
  SettleSpec s;
  const toml::table* t = parent.subtable(key);
  if (!t) return s;
  TableReader r(*t, parent.file(), parent.name(key));
  s.ke_ratio = r.number_or("ke_ratio", s.ke_ratio, 0, kInf, "(dimensionless)", true);
  s.max_time = r.number_or("max_time", s.max_time, 0, kInf, "s");  // 0: no settling
  s.check_every = r.interval_or("check_every", s.check_every, false, "s");
  r.finish();
  return s;
}

// FRAC above 0.2 resolves a contact in fewer than 8 steps: the restitution comes out 10 to 100 %
// off and the contact time up to twice too long (README, "Which FRAC buys which accuracy";
// bench/results/contact.md). Refused unless forced.
void check_frac(TableReader& r, const SimulationSpec& s) {
  if (s.time_step > 0 || s.frac <= kFracHi) return;  // a given time_step: choose_time_step checks it
  const std::string why = "above " + num(kFracHi) +
                          " a contact lasts fewer than 8 steps and the results are wrong (restitution 10 to 100 % off, contact time up "
                          "to 2x; README \"Which FRAC buys which accuracy\", bench/results/contact.md)";
  if (!s.force_time_step)
    r.fail("frac", why + "; take frac <= " + num(kFracHi) + " (default 0.1; 0.07 for 1 % on the restitution), or set "
                         "simulation.force_time_step = true to run with it anyway");
  r.warn("frac", "forced (simulation.force_time_step = true): " + why);
}

// |g| is 0 or near Earth's 9.81 m/s^2 in a granular scene; far from that, a unit is likely wrong.
void check_gravity(TableReader& r, const Vec3& g) {
  const double a = g.norm();
  if (a == 0 || (a >= kGravityLo && a <= kGravityHi)) return;
  std::string cause = "check the unit (m/s^2 expected)";
  if (a < kGravityLo) cause = "is it in units of g? (m/s^2 expected: 1 g = 9.81 m/s^2)";
  else if (std::abs(a / 981 - 1) < 0.05) cause = "is it in cm/s^2? (m/s^2 expected)";
  else if (std::abs(a / 9810 - 1) < 0.05) cause = "is it in mm/s^2, lengths in mm? (m/s^2 expected)";
  r.warn("gravity", "|g| = " + num(a) + " m/s^2, outside 0 and [" + num(kGravityLo) + ", " + num(kGravityHi) +
                        "] m/s^2 (the Moon's 1.62 to Jupiter's 24.8; Earth's 9.81): " + cause);
}

void read_simulation(TableReader& top, Scene& sc) {
  const toml::table* t = top.subtable("simulation");
  if (!t) return;
  TableReader r(*t, top.file(), "simulation");
  SimulationSpec& s = sc.simulation;
  s.time_step = r.number_or("time_step", 0.0, 0, kInf, "s (0 = automatic, docs/physics.md eq. P5)");
  s.frac = r.number_or("frac", s.frac, 0, 1, "(fraction of the critical step, docs/physics.md eq. P5)", true);
  s.force_time_step = r.boolean_or("force_time_step", false);
  s.gravity = r.vec3_or("gravity", s.gravity);
  s.alpha_r = r.number_or("alpha_r", 0.0, 0, kInf, "1/s");
  s.alpha_theta = r.number_or("alpha_theta", 0.0, 0, kInf, "1/s");
  s.skin = r.number_or("skin", 0.0, 0, kInf, "m (0 = 0.2 x mean radius)");
  s.max_overlap = r.number_or("max_overlap", s.max_overlap, 0, 2, "(fraction of the smaller radius)", true);
  s.max_energy_gain = r.number_or("max_energy_gain", s.max_energy_gain, 0, kInf, "(fraction of the energy scale; 0 = no check)");
  s.sort_every = r.integer_or("sort_every", s.sort_every, 0, 1000000000);
  if (const toml::table* pt = r.subtable("periodic")) {
    TableReader pr(*pt, r.file(), r.name("periodic"));
    for (int d = 0; d < 3; ++d) {
      const std::string axis(1, "xyz"[d]);
      const toml::node* n = pr.node(axis);
      if (!n) continue;
      const toml::array* a = n->as_array();
      const auto finite = [&](std::size_t k) { return a->get(k)->is_number() && std::isfinite(*a->get(k)->value<double>()); };
      if (!a || a->size() != 2 || !finite(0) || !finite(1))
        pr.fail_at(n, axis, "expected [lo, hi] in m: the period along " + axis);
      const double lo = *a->get(0)->value<double>(), hi = *a->get(1)->value<double>();
      if (!(hi > lo)) pr.fail_at(n, axis, "hi must exceed lo");
      s.periodic.axis[d] = true;
      s.periodic.lo[d] = lo;
      s.periodic.hi[d] = hi;
    }
    pr.finish();
    if (!s.periodic.any()) r.fail("periodic", "give the period along at least one axis, e.g. { x = [0.0, 0.04] }");
    for (int d = 0; d < 3; ++d)
      if (s.periodic.axis[d] && s.periodic.hi[d] - s.periodic.lo[d] > kExtentHi)
        pr.warn(std::string(1, "xyz"[d]), "a period of " + num(s.periodic.hi[d] - s.periodic.lo[d]) + " m, above the " + num(kExtentHi) +
                                               " m of a granular scene: lengths in mm? (m expected)");
  }
  check_frac(r, s);
  check_gravity(r, s.gravity);
  r.finish();
}

const std::string kCundall = "cundall";

NormalLaw read_law(TableReader& r, const std::string* def) {
  return *normal_law_named(r.choice("law", normal_law_names(), def));  // the table's keywords
}
const std::string kCoulomb = "coulomb";
TangentialLaw read_tangential(TableReader& r, const std::string* def) {
  return *tangential_law_named(r.choice("tangential", tangential_law_names(), def));
}
const std::string kNone = "none";
RollingLaw read_rolling(TableReader& r, const std::string* def) {
  return *rolling_law_named(r.choice("rolling", rolling_law_names(), def));
}
std::string models_text(ModelChoice m) {
  return "law = \"" + std::string(normal_law_name(m.normal)) + "\", tangential = \"" + std::string(tangential_law_name(m.tangential)) +
         "\", rolling = \"" + std::string(rolling_law_name(m.rolling)) + "\"";
}

// One contact property by its key (contact/properties.hpp), stored in `into`; returns it.
double read_property(TableReader& r, const PropertyKey& k, ContactProperties& into) {
  const std::string key(k.keyword);
  if (k.flag) return into.*k.flag = r.boolean_or(key, false);
  return into.*k.number = r.number(key, k.lo, k.hi, std::string(k.unit).c_str(), k.lo_open, k.hi_open);
}

bool reads_key(const std::vector<PropertyKey>& keys, std::string_view keyword) {
  return std::any_of(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == keyword; });
}

// Plausibility of the stiffnesses and moduli given in one table (docs/scene.md, "Warnings").
void check_properties(TableReader& r, const std::vector<PropertyKey>& keys, const ContactProperties& c) {
  for (const PropertyKey& k : keys) {
    const std::string key(k.keyword);
    if (k.flag || !r.node(key)) continue;
    const double v = c.*k.number;
    if (key == "kn" || key == "kt") {
      if (v >= kStiffnessLo && v <= kStiffnessHi) continue;
      r.warn(key, key + " = " + num(v) + " N/m, outside [" + num(kStiffnessLo) + ", " + num(kStiffnessHi) + "] N/m of granular contacts: " +
                      (v < kStiffnessLo ? "is it in kN/m or MN/m? (N/m expected)" : "check the unit (N/m expected)"));
    } else if (key == "young_modulus") {
      if (v >= kModulusLo && v <= kModulusHi) continue;
      std::string cause = "stiffer than diamond (1.2e12 Pa): check the unit (Pa expected)";
      if (v < kModulusLo) cause = v * 1e9 <= kModulusHi ? "is it in GPa or MPa? (Pa expected: 70 GPa = 7e10 Pa)" : "is it in MPa? (Pa expected)";
      r.warn(key, "E = " + num(v) + " Pa, outside [" + num(kModulusLo) + ", " + num(kModulusHi) + "] Pa (soft rubber to diamond): " + cause);
    }
  }
}

// A key that only other laws' models read is an error that says whose it is.
void refuse_keys_of_other_laws(TableReader& r, ModelChoice models) {
  const std::vector<PropertyKey> own = property_keys(models);
  for (const PropertyKey& k : all_property_keys()) {
    const std::string key(k.keyword);
    if (reads_key(own, k.keyword) || !r.has(key)) continue;
    r.fail(key, "a property of " + laws_reading(k.keyword) + ", not of these laws (" + models_text(models) + ")");
  }
}

// [[pair]] materials = ["a", "b"] with any material contact key: explicit values for that pair.
void read_pairs(TableReader& top, Scene& sc) {
  const auto list = top.tables("pair");
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], top.file(), indexed("pair", k));
    PairOverride o;
    const toml::node& mn = r.required("materials");
    const toml::array* a = mn.as_array();
    if (!a || a->size() != 2) r.fail_at(&mn, "materials", "expected two material names, e.g. [\"sand\", \"steel\"]");
    int idx[2];
    for (int e = 0; e < 2; ++e) {
      const std::string name = r.string_of(*a->get(e), "materials");
      idx[e] = find_material(sc.materials, name);
      if (idx[e] < 0) r.fail_at(&mn, "materials", "no material named \"" + name + "\"");
    }
    o.a = idx[0];
    o.b = idx[1];
    for (const PairOverride& x : sc.pairs)
      if ((x.a == o.a && x.b == o.b) || (x.a == o.b && x.b == o.a)) r.fail_at(&mn, "materials", "a [[pair]] for these materials is already given");
    if (r.has("law")) o.law = read_law(r, nullptr);
    if (r.has("tangential")) o.tangential = read_tangential(r, nullptr);
    if (r.has("rolling")) o.rolling = read_rolling(r, nullptr);
    const ModelChoice models = o.models(sc.materials[o.a]);
    refuse_keys_of_other_laws(r, models);
    const std::vector<PropertyKey> keys = property_keys(models);
    // A law that reads a property of each material (not mixed) joins only materials that give it.
    for (const PropertyKey& k : keys)
      for (const int side : {o.a, o.b}) {
        const Material& m = sc.materials[side];
        if (!k.mixing && !k.flag && !reads_key(property_keys(m.models()), k.keyword))
          r.fail_at(&mn, "materials", "the pair's laws (" + models_text(models) + ") read " + std::string(k.keyword) +
                                          " of each material, and material \"" + m.name + "\" (" + models_text(m.models()) +
                                          ") has none");
      }
    for (const PropertyKey& k : keys) {
      if (!r.has(std::string(k.keyword))) continue;
      if (!k.mixing && !k.flag)
        r.fail(std::string(k.keyword), "a property of each material, which the law combines itself: give it in the [[material]]");
      o.set(k.keyword, read_property(r, k, o.values));
    }
    check_properties(r, keys, o.values);
    r.finish();
    sc.pairs.push_back(o);
  }
  // Unlike laws have no mixing rule: the pair must say which law applies.
  for (std::size_t x = 0; x < sc.materials.size(); ++x)
    for (std::size_t y = x + 1; y < sc.materials.size(); ++y) {
      const Material &mx = sc.materials[x], &my = sc.materials[y];
      const auto check = [&](bool same, const char* kind, const char* key, auto gives, const std::vector<std::string>& allowed) {
        if (same) return;
        bool given = false;
        for (const PairOverride& o : sc.pairs)
          given = given || (((o.a == int(x) && o.b == int(y)) || (o.a == int(y) && o.b == int(x))) && gives(o));
        if (!given)
          throw InputError(top.file() + ": materials \"" + mx.name + "\" and \"" + my.name + "\" use different " + kind +
                           " laws; add a [[pair]] with materials = [\"" + mx.name + "\", \"" + my.name + "\"] and " + key +
                           " = \"...\" (allowed " + quoted_list(allowed) + ")");
      };
      check(mx.law == my.law, "normal", "law", [](const PairOverride& o) { return o.law.has_value(); }, normal_law_names());
      check(mx.tangential == my.tangential, "tangential", "tangential", [](const PairOverride& o) { return o.tangential.has_value(); },
            tangential_law_names());
      check(mx.rolling == my.rolling, "rolling", "rolling", [](const PairOverride& o) { return o.rolling.has_value(); },
            rolling_law_names());
    }
}

void read_materials(TableReader& top, Scene& sc) {
  const auto list = top.tables("material");
  if (list.empty()) {
    std::ostringstream s;
    s << top.file() << ": no [[material]] defined (at least one is required)";
    throw InputError(s.str());
  }
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], top.file(), indexed("material", k));
    Material m;
    m.name = r.string("name");
    if (find_material(sc.materials, m.name) >= 0) r.fail("name", "duplicate material name");
    m.law = read_law(r, &kCundall);
    m.tangential = read_tangential(r, &kCoulomb);
    m.rolling = read_rolling(r, &kNone);
    m.density = r.number("density", 0, kInf, "kg/m^3", true);
    refuse_keys_of_other_laws(r, m.models());
    const std::vector<PropertyKey> keys = property_keys(m.models());
    for (const PropertyKey& k : keys) {
      const std::string key(k.keyword);
      if (r.has(key)) {
        read_property(r, k, m);
        continue;
      }
      // Omitted: its default, or an earlier key's value, or required.
      const auto from = std::find_if(keys.begin(), keys.end(), [&](const PropertyKey& o) { return o.keyword == k.default_key; });
      if (k.flag) m.*k.flag = k.default_value != 0;
      else if (from != keys.end()) m.*k.number = m.*from->number;
      else if (k.required || !k.default_key.empty()) r.required(key);
      else m.*k.number = k.default_value;
    }
    if (m.density < kDensityLo || m.density > kDensityHi)
      r.warn("density", "density " + num(m.density) + " kg/m^3, outside [" + num(kDensityLo) + ", " + num(kDensityHi) +
                            "] kg/m^3 of granular solids: " +
                            (m.density < kDensityLo ? "is it in g/cm^3? (kg/m^3 expected: 2.5 g/cm^3 = 2500 kg/m^3)"
                                                    : "denser than any solid (osmium: 22590 kg/m^3): check the unit (kg/m^3 expected)"));
    check_properties(r, keys, m);
    r.finish();
    sc.materials.push_back(m);
  }
  if (const toml::table* t = top.subtable("mixing")) {
    TableReader r(*t, top.file(), "mixing");
    sc.mixing.stiffness = read_mix(r, "stiffness", sc.mixing.stiffness);
    sc.mixing.friction = read_mix(r, "friction", sc.mixing.friction);
    sc.mixing.restitution = read_mix(r, "restitution", sc.mixing.restitution);
    sc.mixing.strength = read_mix(r, "strength", sc.mixing.strength);
    r.finish();
  }
  read_pairs(top, sc);
}

void add_wall(TableReader& r, Scene& sc, WallSpec w) {
  for (const WallSpec& o : sc.walls)
    if (o.name == w.name) r.fail("name", "duplicate wall name \"" + w.name + "\"");
  const std::string problem = polygon_problem(w.vertices);
  if (!problem.empty()) r.fail("vertices", problem);
  sc.walls.push_back(std::move(w));
}

// A mesh of more elements than this is refused (a typo in `segments` or `scale` should not eat
// the memory; the thesis's drum has a few thousand quads, fig. 4.4).
constexpr long long kMaxMeshElements = 1000000;

// `keys`: the keys that set the count, as written in the message; the first one given is blamed.
void check_mesh_size(TableReader& r, const std::vector<std::string>& keys, const std::string& formula, long long elements) {
  if (elements <= kMaxMeshElements) return;
  std::string blame = "type";
  for (auto it = keys.rbegin(); it != keys.rend(); ++it)
    if (r.has(*it)) blame = *it;
  r.fail(blame, "the mesh would have " + std::to_string(elements) + " elements (" + formula + "), more than the limit of " +
                    std::to_string(kMaxMeshElements) + " per wall");
}

// Adds the elements of a mesh wall as NAME.0, NAME.1, ... The [[wall]] name is unique and has no
// '.', so these names are new; every element is checked again as a polygon (a safety net).
void add_mesh(TableReader& r, Scene& sc, const std::string& name, int material, std::vector<Polygon> elements,
              const std::string& blame) {
  sc.walls.reserve(sc.walls.size() + elements.size());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const std::string problem = polygon_problem(elements[k]);
    if (!problem.empty()) r.fail(blame, "element " + std::to_string(k) + " of the mesh: " + problem);
    sc.walls.push_back(WallSpec{name + "." + std::to_string(k), material, std::move(elements[k])});
  }
}

Vec3 direction_or(TableReader& r, const std::string& key, const Vec3& def) {
  const Vec3 a = r.vec3_or(key, def);
  if (!(a.norm() > 0)) r.fail(key, "must be a non-zero vector");
  return a;
}

// A required direction, normalised.
Vec3 unit_direction(TableReader& r, const std::string& key) {
  r.required(key);
  return direction_or(r, key, Vec3::Zero()).normalized();
}

int segments_of(TableReader& r, const std::string& key) {
  return static_cast<int>(r.integer_or(key, kDefaultSegments, 3, kMaxMeshElements));
}

// An inner radius in [0, outer): 0 (the default) = none.
double inner_radius_of(TableReader& r, double outer) {
  const double v = r.number_or("inner_radius", 0.0, 0, kInf, "m");
  if (v >= outer) {
    std::ostringstream s;
    s << "out of range: allowed [0, radius) m, radius = " << outer << " m";
    r.fail("inner_radius", s.str());
  }
  return v;
}

std::vector<Polygon> read_rectangle(TableReader& r) {
  const Vec3 corner = r.vec3("corner"), u = r.vec3("edge_u"), v = r.vec3("edge_v");
  if (!(u.norm() > 0)) r.fail("edge_u", "must be a non-zero vector");
  if (!(v.norm() > 0)) r.fail("edge_v", "must be a non-zero vector");
  if (!(u.cross(v).norm() > 1e-12 * u.norm() * v.norm())) r.fail("edge_v", "must not be parallel to edge_u");
  const long nu = r.integer_or("nu", 1, 1, kMaxMeshElements), nv = r.integer_or("nv", 1, 1, kMaxMeshElements);
  static const std::string quads = "quads";
  const bool tri = r.choice("elements", {"quads", "triangles"}, &quads) == "triangles";
  check_mesh_size(r, {"nu", "nv"}, tri ? "2 x nu x nv" : "nu x nv", static_cast<long long>(nu) * nv * (tri ? 2 : 1));
  return rectangle_mesh(corner, u, v, static_cast<int>(nu), static_cast<int>(nv), tri);
}

std::vector<Polygon> read_cylinder(TableReader& r) {
  const Vec3 base = r.vec3("base_centre");
  const Vec3 axis = direction_or(r, "axis", Vec3::UnitZ());
  const double radius = r.number("radius", 0, kInf, "m", true);
  const double height = r.number("height", 0, kInf, "m", true);
  const int segments = segments_of(r, "segments");
  const long rings = r.integer_or("rings", 1, 1, kMaxMeshElements);
  check_mesh_size(r, {"segments", "rings"}, "segments x rings", static_cast<long long>(segments) * rings);
  return cylinder_mesh(base, axis, radius, height, segments, static_cast<int>(rings));
}

std::vector<Polygon> read_disc(TableReader& r) {
  const Vec3 centre = r.vec3("centre");
  const Vec3 normal = direction_or(r, "normal", Vec3::UnitZ());
  const double radius = r.number("radius", 0, kInf, "m", true);
  const double inner = inner_radius_of(r, radius);
  return disc_mesh(centre, normal, radius, inner, segments_of(r, "segments"));
}

std::vector<Polygon> read_cone(TableReader& r) {
  const Vec3 base = r.vec3("base_centre");
  const Vec3 axis = direction_or(r, "axis", Vec3::UnitZ());
  const double rb = r.number("radius_base", 0, kInf, "m");
  const double rt = r.number("radius_top", 0, kInf, "m");
  if (rb == 0 && rt == 0) r.fail("radius_top", "radius_base and radius_top are both 0: at least one must be > 0");
  const double height = r.number("height", 0, kInf, "m", true);
  return cone_mesh(base, axis, rb, rt, height, segments_of(r, "segments"));
}

std::vector<Polygon> read_helix(TableReader& r) {
  const Vec3 base = r.vec3("base_centre");
  const Vec3 axis = direction_or(r, "axis", Vec3::UnitZ());
  const double radius = r.number("radius", 0, kInf, "m", true);
  const double inner = inner_radius_of(r, radius);
  const double pitch = r.number("pitch", -kInf, kInf, "m");
  if (pitch == 0) r.fail("pitch", "must be non-zero (rise per turn; negative for a left-handed helix)");
  const double turns = r.number("turns", 0, kInf, "(turns)", true);
  const int spt = segments_of(r, "segments_per_turn");
  const int bands = static_cast<int>(r.integer_or("radial_segments", 1, 1, kMaxMeshElements));
  check_mesh_size(r, {"turns", "segments_per_turn", "radial_segments"}, "2 x ceil(turns x segments_per_turn) x radial_segments",
                  helical_ramp_elements(turns, spt, bands));
  return helical_ramp_mesh(base, axis, inner, radius, pitch, turns, spt, bands);
}

// The files read while parsing one scene (parse_scene sets it): STL files are reached from deep
// inside nested readers (walls, regions of cuts and actions) that do not carry the Scene.
thread_local std::vector<std::string>* files_read = nullptr;

void note_file_read(const std::string& path) {
  if (!files_read) return;
  const std::string entry = file_fingerprint(path) + " " + path;  // IoError: reported at the `file` key
  if (std::find(files_read->begin(), files_read->end(), entry) == files_read->end()) files_read->push_back(entry);
}

// STL triangles, transformed x -> R·(scale·x) + translate. The file is found relative to the
// scene file's directory; a file that cannot be read is reported at the `file` key.
std::vector<Polygon> read_stl_wall(TableReader& r) {
  const toml::node& fn = r.required("file");
  const std::string file = r.string_of(fn, "file");
  if (file.empty()) r.fail_at(&fn, "file", "expected a file name");
  std::filesystem::path path(file);
  if (path.is_relative()) path = std::filesystem::path(r.file()).parent_path() / path;
  const double scale = r.number_or("scale", 1.0, 0, kInf, "(multiplies the file's coordinates, e.g. 0.001 for mm)", true);
  const Vec3 translate = r.vec3_or("translate", Vec3::Zero());
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  if (const toml::table* t = r.subtable("rotate")) {
    TableReader rr(*t, r.file(), r.name("rotate"));
    const Vec3 axis = direction_or(rr, "axis", Vec3::UnitZ());
    const double angle = rr.number("angle", -kInf, kInf, "degrees");
    rr.finish();
    rot = Eigen::AngleAxisd(angle * M_PI / 180, axis.normalized()).toRotationMatrix();
  }
  const bool skip = r.boolean_or("skip_degenerate", false);
  std::vector<Triangle> tris;
  try {
    tris = read_stl(path.string());
    note_file_read(path.string());
  } catch (const IoError& e) {
    r.fail_at(&fn, "file", e.what());
  }
  check_mesh_size(r, {"file"}, "triangles in the file", static_cast<long long>(tris.size()));
  const std::size_t total = tris.size();
  std::size_t first = 0;
  const std::size_t bad = remove_degenerate(tris, &first);
  if (bad > 0 && !skip)
    r.fail_at(&fn, "file", path.string() + ": " + std::to_string(bad) + " of " + std::to_string(total) +
                               " triangles are degenerate (zero area; the first is triangle " + std::to_string(first) +
                               ", counting from 0); set skip_degenerate = true to drop them");
  if (tris.empty()) r.fail_at(&fn, "file", path.string() + ": every triangle is degenerate (zero area)");
  std::vector<Polygon> out;
  out.reserve(tris.size());
  for (const Triangle& t : tris) {
    Polygon p;
    for (const Vec3& v : t) p.push_back(rot * (scale * v) + translate);
    out.push_back(std::move(p));
  }
  return out;
}

void read_walls(TableReader& top, Scene& sc) {
  const auto list = top.tables("wall");
  std::map<std::string, std::size_t> names;  // [[wall]] name -> its index, for duplicates
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], top.file(), indexed("wall", k));
    const std::string name = r.string("name");
    if (name.find('.') != std::string::npos) r.fail("name", "a wall name must not contain '.' (reserved for groups)");
    if (const auto it = names.find(name); it != names.end())
      r.fail("name", "duplicate wall name \"" + name + "\" (also " + indexed("wall", it->second) + ")");
    names.emplace(name, k);
    const std::size_t first_element = sc.walls.size();
    const int mat = material_ref(r, "material", sc.materials);
    const std::string type = r.choice("type", {"polygon", "box", "rectangle", "cylinder", "disc", "cone", "helix", "stl"});
    if (type == "polygon") {
      const toml::node& vn = r.required("vertices");
      const toml::array* a = vn.as_array();
      if (!a || (a->size() != 3 && a->size() != 4)) r.fail_at(&vn, "vertices", "expected 3 or 4 vertices [[x,y,z], ...]");
      WallSpec w{name, mat, {}};
      for (const toml::node& e : *a) w.vertices.push_back(r.vec3_of(e, "vertices"));
      add_wall(r, sc, std::move(w));
    } else if (type == "box") {
      const Vec3 lo = r.vec3("min"), hi = r.vec3("max");
      if (!((hi - lo).array() > 0).all()) r.fail("max", "every component of max must exceed min");
      static const std::vector<std::string> all = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
      std::vector<std::string> faces = all;
      if (const toml::node* fn = r.node("faces")) {
        const toml::array* a = fn->as_array();
        if (!a || a->empty()) r.fail_at(fn, "faces", "expected a non-empty array of face names");
        faces.clear();
        for (const toml::node& e : *a) {
          const std::string f = r.string_of(e, "faces");
          if (std::find(all.begin(), all.end(), f) == all.end())
            r.fail_at(fn, "faces", "unknown face \"" + f + "\": allowed xmin, xmax, ymin, ymax, zmin, zmax");
          faces.push_back(f);
        }
      }
      for (const std::string& f : faces) {
        add_wall(r, sc, WallSpec{name + "." + f, mat, box_face(lo, hi, f[0] - 'x', f.substr(1) == "max")});
      }
    } else {
      // Mesh walls (SPEC §3): elements NAME.0, NAME.1, ... sharing the wall's material.
      std::vector<Polygon> mesh;
      try {
        mesh = type == "rectangle" ? read_rectangle(r)
               : type == "cylinder" ? read_cylinder(r)
               : type == "disc"     ? read_disc(r)
               : type == "cone"     ? read_cone(r)
               : type == "helix"    ? read_helix(r)
                                    : read_stl_wall(r);
      } catch (const std::invalid_argument& e) {
        r.fail("type", e.what());  // a primitive's own check; the readers above check first
      }
      add_mesh(r, sc, name, mat, std::move(mesh), type == "stl" ? "file" : "type");
    }
    Vec3 lo = Vec3::Constant(kInf), hi = -lo;
    for (std::size_t e = first_element; e < sc.walls.size(); ++e)
      for (const Vec3& v : sc.walls[e].vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    if (sc.walls.size() > first_element && (hi - lo).maxCoeff() > kExtentHi)
      r.warn("type", "wall \"" + name + "\" spans " + num((hi - lo).maxCoeff()) + " m, above the " + num(kExtentHi) +
                         " m of a granular scene: lengths in mm? (m expected" + (type == "stl" ? "; scale = 0.001 reads a file in mm)" : ")"));
    r.finish();
  }
}

// [[generation.place]]: spheres at given positions (e.g. the large intruder of the segregation
// case), inside the generation box and not overlapping each other.
std::vector<PlacedSphere> read_placed(TableReader& gen, const Scene& sc, const GenerationSpec& g) {
  std::vector<PlacedSphere> out;
  const auto list = gen.tables("place");
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], gen.file(), gen.name(indexed("place", k)));
    PlacedSphere s;
    s.centre = r.vec3("centre");
    s.radius = r.number("radius", 0, kInf, "m", true);
    if (s.radius > kRadiusHi)
      r.warn("radius", "radius " + num(s.radius) + " m, above the " + num(kRadiusHi) + " m of a granular particle: lengths in mm? (m expected)");
    const std::string mat = r.string("material");
    s.material = find_material(sc.materials, mat);
    if (s.material < 0) r.fail("material", "no material of that name");
    if (!((s.centre.array() - s.radius >= g.box_min.array()).all() && (s.centre.array() + s.radius <= g.box_max.array()).all()))
      r.fail("centre", "the sphere (centre +- radius) must lie inside the generation box [box_min, box_max]");
    for (std::size_t j = 0; j < out.size(); ++j)
      if ((out[j].centre - s.centre).norm() < out[j].radius + s.radius)
        r.fail("centre", "overlaps generation.place[" + std::to_string(j) + "]");
    r.finish();
    out.push_back(s);
  }
  return out;
}

Region read_region(TableReader& parent, const std::string& key);

// [[generation.cut]]: regions cut out of the settled primary set, in file order (SPEC §9 step 4).
std::vector<CutSpec> read_cuts(TableReader& gen) {
  std::vector<CutSpec> out;
  const auto list = gen.tables("cut");
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], gen.file(), gen.name(indexed("cut", k)));
    CutSpec c;
    c.region = read_region(r, "region");
    c.inside = r.boolean_or("inside", true);
    r.finish();
    out.push_back(std::move(c));
  }
  return out;
}

// One row of generation.size.sieve: [diameter (m), cumulative mass fraction passing], checked
// against the row before it.
std::pair<double, double> read_sieve_row(TableReader& r, const toml::node& e, std::size_t k, const std::pair<double, double>* prev) {
  const std::string key = indexed("sieve", k);
  const toml::array* row = e.as_array();
  if (!row || row->size() != 2 || !row->get(0)->is_number() || !row->get(1)->is_number())
    r.fail_at(&e, key, "expected a row [diameter (m), cumulative mass fraction passing]");
  const double d = *row->get(0)->value<double>(), f = *row->get(1)->value<double>();
  std::ostringstream v;
  v << "[" << d << ", " << f << "]: ";
  if (!std::isfinite(d) || !(d > 0)) r.fail_at(&e, key, v.str() + "the diameter must be > 0 m");
  if (!(f >= 0 && f <= 1)) r.fail_at(&e, key, v.str() + "the fraction passing must be in [0, 1]");
  if (prev && !(d > prev->first)) {
    std::ostringstream m;
    m << v.str() << "diameters must increase row by row (" << d << " m is not above row " << k - 1 << "'s " << prev->first << " m)";
    r.fail_at(&e, key, m.str());
  }
  if (prev && f < prev->second) {
    std::ostringstream m;
    m << v.str() << "fractions passing must not decrease (" << f << " is below row " << k - 1 << "'s " << prev->second << ")";
    r.fail_at(&e, key, m.str());
  }
  if (!prev && f != 0) r.fail_at(&e, key, v.str() + "the first row's fraction passing must be 0 (no mass below the smallest sieve)");
  return {d, f};
}

// generation.size.sieve = [[d0, 0.0], ..., [dn, 1.0]]: a sieve curve, diameters increasing.
std::vector<std::pair<double, double>> read_sieve(TableReader& r) {
  const toml::node& n = r.required("sieve");
  const toml::array* a = n.as_array();
  if (!a || a->size() < 2) r.fail_at(&n, "sieve", "expected at least 2 rows [diameter (m), cumulative mass fraction passing]");
  std::vector<std::pair<double, double>> rows;
  for (std::size_t k = 0; k < a->size(); ++k) rows.push_back(read_sieve_row(r, *a->get(k), k, rows.empty() ? nullptr : &rows.back()));
  if (rows.back().second != 1) {
    std::ostringstream m;
    m << "the last row's fraction passing is " << rows.back().second << ": it must be 1 (all the mass passes the largest sieve)";
    r.fail_at(a->get(a->size() - 1), indexed("sieve", a->size() - 1), m.str());
  }
  return rows;
}

// [generation.size]: the size distribution (generation/size_distribution.hpp); uniform when absent.
SizeSpec read_size(TableReader& gen) {
  SizeSpec s;
  const toml::table* t = gen.subtable("size");
  if (!t) return s;
  TableReader r(*t, gen.file(), gen.name("size"));
  s.given = true;
  static const std::vector<std::string> names = {"uniform", "normal", "lognormal", "sieve"};
  const std::string kind = r.choice("distribution", names);
  s.kind = static_cast<SizeSpec::Kind>(std::find(names.begin(), names.end(), kind) - names.begin());
  if (s.kind == SizeSpec::Kind::Normal) {
    s.mean_radius = r.number("mean_radius", 0, kInf, "m", true);
    s.std_radius = r.number("std_radius", 0, kInf, "m", true);
  } else if (s.kind == SizeSpec::Kind::LogNormal) {
    s.median_radius = r.number("median_radius", 0, kInf, "m", true);
    s.geometric_std = r.number("geometric_std", 1, kInf, "(dimensionless)", true);
  } else if (s.kind == SizeSpec::Kind::Sieve) {
    s.sieve = read_sieve(r);
  }
  r.finish();
  return s;
}

// The normal and log-normal must keep a fair share of their mass within [radius_min, radius_max]:
// else the truncated draw piles up at one bound.
void check_truncation(TableReader& gen, const GenerationSpec& g) {
  const double mass = truncated_mass(g.size, g.radius_min, g.radius_max);
  if (mass >= kMinTruncatedMass) return;
  TableReader r(*gen.subtable("size"), gen.file(), gen.name("size"));
  const bool normal = g.size.kind == SizeSpec::Kind::Normal;
  std::ostringstream m;
  m << "only a fraction " << mass << " of the " << (normal ? "normal" : "log-normal") << " distribution lies in [radius_min, radius_max] = ["
    << g.radius_min << ", " << g.radius_max << "] m (at least " << kMinTruncatedMass << " is needed): move "
    << (normal ? "mean_radius, widen std_radius" : "median_radius, widen geometric_std") << " or the bounds";
  r.fail(normal ? "mean_radius" : "median_radius", m.str());
}

// radius_min and radius_max: given, or (sieve) the curve's first and last diameters / 2.
void read_radius_bounds(TableReader& r, GenerationSpec& g) {
  const double smallest = (g.box_max - g.box_min).minCoeff();
  if (g.size.kind == SizeSpec::Kind::Sieve) {
    for (const char* key : {"radius_min", "radius_max"})
      if (r.has(key)) r.fail(key, "not used with generation.size.distribution = \"sieve\": the curve's first and last diameters bound the sizes");
    g.radius_min = 0.5 * g.size.sieve.front().first;
    g.radius_max = 0.5 * g.size.sieve.back().first;
    if (2 * g.radius_max > smallest) r.fail("size", "the largest sieve diameter does not fit in the generation box");
    return;
  }
  g.radius_min = r.number("radius_min", 0, kInf, "m", true);
  g.radius_max = r.number("radius_max", 0, kInf, "m", true);
  if (g.radius_min > g.radius_max) r.fail("radius_max", "radius_max must be >= radius_min (" + std::to_string(g.radius_min) + " m)");
  if (2 * g.radius_max > smallest) r.fail("radius_max", "a sphere of this radius does not fit in the generation box");
  check_truncation(r, g);
}

// materials = { name = fraction, ... } (fractions summing to 1).
std::vector<std::pair<int, double>> read_fractions(TableReader& r, const Scene& sc) {
  const toml::node& mn = r.required("materials");
  const toml::table* mt = mn.as_table();
  if (!mt || mt->empty()) r.fail_at(&mn, "materials", "expected a table of material = fraction, e.g. { glass = 1.0 }");
  TableReader mr(*mt, r.file(), r.name("materials"));
  std::vector<std::pair<int, double>> out;
  double sum = 0;
  for (const auto& [k, v] : *mt) {
    const std::string name(k.str());
    const int idx = find_material(sc.materials, name);
    if (idx < 0) mr.fail_at(&v, name, "no material of that name");
    const double f = mr.number(name, 0, 1, "(fraction)", true);
    sum += f;
    out.emplace_back(idx, f);
  }
  if (std::abs(sum - 1) > 1e-9) r.fail_at(&mn, "materials", "the fractions must sum to 1 (they sum to " + std::to_string(sum) + ")");
  return out;
}

void read_generation(TableReader& top, Scene& sc) {
  const toml::table* t = top.subtable("generation");
  if (!t) return;
  TableReader r(*t, top.file(), "generation");
  GenerationSpec g;
  g.box_min = r.vec3("box_min");
  g.box_max = r.vec3("box_max");
  if (!((g.box_max - g.box_min).array() > 0).all()) r.fail("box_max", "every component of box_max must exceed box_min");
  const PeriodicBox& period = sc.simulation.periodic;
  for (int d = 0; d < 3; ++d)
    if (period.axis[d] && (g.box_min[d] < period.lo[d] || g.box_max[d] > period.hi[d]))
      r.fail("box_max", std::string("along the periodic axis ") + "xyz"[d] +
                            " the generation box must lie within simulation.periodic (spheres placed across the boundary could overlap)");
  if ((g.box_max - g.box_min).maxCoeff() > kExtentHi)
    r.warn("box_max", "the generation box spans " + num((g.box_max - g.box_min).maxCoeff()) + " m, above the " + num(kExtentHi) +
                          " m of a granular scene: lengths in mm? (m expected)");
  g.count = static_cast<int>(r.integer("count", 0, 100000000));
  g.size = read_size(r);
  read_radius_bounds(r, g);
  if (g.radius_max > kRadiusHi)
    r.warn(g.size.kind == SizeSpec::Kind::Sieve ? "size" : "radius_max",
           "spheres of radius up to " + num(g.radius_max) + " m, above the " + num(kRadiusHi) + " m of a granular particle: lengths in mm? (m expected)");
  g.seed = static_cast<std::uint64_t>(r.integer_or("seed", 1, 0, std::numeric_limits<long>::max()));
  g.material_fractions = read_fractions(r, sc);
  g.placed = read_placed(r, sc, g);
  if (g.count == 0 && g.placed.empty()) r.fail("count", "no spheres: give count >= 1 or [[generation.place]] entries");
  g.settle = read_settle(r, "settle");
  g.cuts = read_cuts(r);
  r.finish();
  sc.generation = g;
}

void read_copy(TableReader& top, Scene& sc) {
  const toml::table* t = top.subtable("copy");
  if (!t) return;
  TableReader r(*t, top.file(), "copy");
  CopySpec c;
  c.nx = static_cast<int>(r.integer_or("nx", 1, 1, 1000));
  c.ny = static_cast<int>(r.integer_or("ny", 1, 1, 1000));
  c.nz = static_cast<int>(r.integer_or("nz", 1, 1, 1000));
  if (r.has("spacing")) {
    c.spacing = r.vec3("spacing");
    if (!(c.spacing->array() > 0).all()) r.fail("spacing", "every component must be > 0 m");
  }
  c.settle = read_settle(r, "settle");
  r.finish();
  sc.copy = c;
}

void read_compact(TableReader& top, Scene& sc) {
  const toml::table* t = top.subtable("compact");
  if (!t) return;
  TableReader r(*t, top.file(), "compact");
  CompactSpec c;
  const toml::node& wn = r.required("walls");
  const toml::array* a = wn.as_array();
  if (!a || a->empty()) r.fail_at(&wn, "walls", "expected a non-empty array of wall names");
  for (const toml::node& e : *a) {
    const std::string w = r.string_of(e, "walls");
    bool found = false;
    for (const WallSpec& s : sc.walls) found = found || wall_matches(s.name, w);
    if (!found) r.fail_at(&wn, "walls", "no wall or wall group named \"" + w + "\"");
    c.walls.push_back(w);
  }
  c.speed = r.number("speed", 0, kInf, "m/s", true);
  c.target_stress = r.number_or("target_stress", 0.0, 0, kInf, "Pa", true);
  c.target_porosity = r.number_or("target_porosity", 0.0, 0, 1, "(dimensionless)", true, true);
  if ((c.target_stress > 0) == (c.target_porosity > 0)) r.fail("target_stress", "give exactly one of target_stress and target_porosity");
  c.max_time = r.number_or("max_time", c.max_time, 0, kInf, "s", true);
  c.settle = read_settle(r, "settle");
  r.finish();
  sc.compact = c;
}

// region = { type = "cylinder", ... }: a point on the axis, the axis (default +z), the radius, and
// optionally the length (centred on `centre`; infinite when not given, e.g. a borehole through
// the whole sample).
void read_cylinder_region(TableReader& r, Region& g) {
  g.kind = Region::Kind::Cylinder;
  g.centre = r.vec3("centre");
  g.axis = direction_or(r, "axis", Vec3::UnitZ()).normalized();
  g.radius = r.number("radius", 0, kInf, "m", true);
  g.length = r.number_or("length", 0.0, 0, kInf, "m (omit for an infinite cylinder)", true);
}

// region = { type = "half_space", point = [...], normal = [...] }: the side the normal points into.
void read_half_space_region(TableReader& r, Region& g) {
  g.kind = Region::Kind::HalfSpace;
  g.point = r.vec3("point");
  g.normal = unit_direction(r, "normal");
}

// region = { type = "mesh", file = "...", ... }: the inside of a closed STL surface, read and placed
// as an STL wall is (file relative to the scene, scale, rotate, translate, skip_degenerate).
void read_mesh_region(TableReader& r, Region& g) {
  g.kind = Region::Kind::Mesh;
  std::vector<std::array<Vec3, 3>> triangles;
  for (const Polygon& t : read_stl_wall(r)) triangles.push_back({t[0], t[1], t[2]});
  try {
    g.mesh = std::make_shared<const ClosedMesh>(std::move(triangles));
  } catch (const std::invalid_argument& e) {
    r.fail("file", e.what());
  }
}

Region read_region(TableReader& parent, const std::string& key) {
  const toml::node& n = parent.required(key);
  if (!n.is_table()) parent.fail_at(&n, key, "expected a table, e.g. { type = \"box\", min = [...], max = [...] }");
  TableReader r(*n.as_table(), parent.file(), parent.name(key));
  Region g;
  const std::string type = r.choice("type", {"box", "sphere", "cylinder", "half_space", "mesh"});
  if (type == "box") {
    g.kind = Region::Kind::Box;
    g.min = r.vec3("min");
    g.max = r.vec3("max");
    if (!((g.max - g.min).array() > 0).all()) r.fail("max", "every component of max must exceed min");
  } else if (type == "sphere") {
    g.kind = Region::Kind::Sphere;
    g.centre = r.vec3("centre");
    g.radius = r.number("radius", 0, kInf, "m", true);
  } else if (type == "cylinder") {
    read_cylinder_region(r, g);
  } else if (type == "half_space") {
    read_half_space_region(r, g);
  } else {
    read_mesh_region(r, g);
  }
  r.finish();
  return g;
}

// The `wall` key of a table: a name that selects at least one wall (or group) of the scene.
std::string wall_ref(TableReader& r, const Scene& sc) {
  const toml::node& wn = r.required("wall");
  const std::string name = r.string_of(wn, "wall");
  bool found = false;
  for (const WallSpec& w : sc.walls) found = found || wall_matches(w.name, name);
  if (!found) r.fail_at(&wn, "wall", "no wall or wall group of that name");
  return name;
}

void read_motion(TableReader& r, MotionSpec& ms) {
  using Part = MotionSpec::Part;
  WallMotion& m = ms.motion;
  const std::string type = r.choice("type", {"fixed", "translate", "table", "vibrate", "rotate"});
  if (type == "translate") {
    ms.part = Part::Translate;
    m.velocity = r.vec3("velocity");
  } else if (type == "table") {
    ms.part = Part::Table;
    const toml::node& tn = r.required("table");
    const toml::array* rows = tn.as_array();
    if (!rows || rows->size() < 2) r.fail_at(&tn, "table", "expected at least 2 rows [t, x, y, z] (s, m)");
    for (const toml::node& row : *rows) {
      const toml::array* a = row.as_array();
      if (!a || a->size() != 4) r.fail_at(&row, "table", "expected a row [t, x, y, z]: time since the stage start [s], displacement [m]");
      double v[4];
      for (int c = 0; c < 4; ++c) v[c] = r.number_of(*a->get(c), "table", -kInf, kInf, c ? "m" : "s");
      if (m.table_time.empty() ? v[0] != 0 : !(v[0] > m.table_time.back()))
        r.fail_at(&row, "table", m.table_time.empty() ? "the first row must be at t = 0 (the stage start)" : "times must increase strictly");
      m.table_time.push_back(v[0]);
      m.table_offset.emplace_back(v[1], v[2], v[3]);
    }
    // The wall starts where it is: displacements count from the first row.
    const Vec3 first = m.table_offset.front();
    for (Vec3& d : m.table_offset) d -= first;
  } else if (type == "vibrate") {
    ms.part = Part::Vibrate;
    m.direction = unit_direction(r, "direction");
    m.frequency = r.number("frequency", 0, kInf, "Hz", true);
    const bool amp = r.has("amplitude"), acc = r.has("acceleration");
    if (amp == acc) r.fail(amp ? "acceleration" : "amplitude", "give exactly one of amplitude [m] and acceleration [m/s^2]");
    if (amp) {
      m.amplitude = r.number("amplitude", 0, kInf, "m", true);
    } else {
      // Peak acceleration A (2 pi f)^2, e.g. "3 g" = 29.43 m/s^2 (SPEC §3).
      const double w = 2 * M_PI * m.frequency;
      m.amplitude = r.number("acceleration", 0, kInf, "m/s^2", true) / (w * w);
    }
    // A vibration table or shaker moves by mm to cm at 1 to 20 g; beyond, the amplitude's unit is likely wrong.
    const double w = 2 * M_PI * m.frequency, peak = m.amplitude * w * w;
    if (m.amplitude > kAmplitudeHi || peak > kVibrationHi)
      r.warn(amp ? "amplitude" : "acceleration",
             "amplitude " + num(m.amplitude) + " m at " + num(m.frequency) + " Hz: peak speed " + num(m.amplitude * w) + " m/s, peak acceleration " +
                 num(peak / 9.81) + " g (a granular vibration: amplitude below " + num(kAmplitudeHi) + " m, below " + num(kVibrationHi / 9.81) +
                 " g): " + (amp ? "amplitude in mm? (m expected)" : "check the unit and the frequency (m/s^2 and Hz expected)"));
  } else if (type == "rotate") {
    ms.part = Part::Rotate;
    m.axis = unit_direction(r, "axis");
    m.centre = r.vec3("centre");
    const double rpm = r.number("rpm", -1e6, 1e6, "rev/min");
    if (rpm == 0) r.fail("rpm", "a rotation needs a non-zero speed (use type = \"fixed\" to stop a wall)");
    m.angular_speed = rpm * 2 * M_PI / 60;  // [rad/s], sign by the right-hand rule about `axis`
  }
}

// [[stage.insert]]: particles poured into a region during the stage (generation/insertion.hpp).
InsertSpec read_insert(TableReader& r, const Scene& sc, double duration) {
  InsertSpec g;
  g.region = read_region(r, "region");
  Vec3 lo, hi;
  if (!region_bounds(g.region, lo, hi))
    r.fail("region", "particles are inserted into a bounded region: a box, a sphere, a cylinder with a length, or a mesh");
  const PeriodicBox& period = sc.simulation.periodic;
  for (int d = 0; d < 3; ++d)
    if (period.axis[d] && (lo[d] < period.lo[d] || hi[d] > period.hi[d]))
      r.fail("region", std::string("along the periodic axis ") + "xyz"[d] + " the insertion region must lie within simulation.periodic");
  // The materials: one by name, or fractions as [generation] gives them.
  const bool one = r.has("material"), mixed = r.has("materials");
  if (one == mixed) r.fail(one ? "materials" : "material", "give exactly one of material = \"name\" and materials = { name = fraction, ... }");
  if (one) g.material_fractions = {{material_ref(r, "material", sc.materials), 1.0}};
  else g.material_fractions = read_fractions(r, sc);
  // The sizes, as [generation] and [generation.size] give them.
  g.size = read_size(r);
  if (g.size.kind == SizeSpec::Kind::Sieve) {
    for (const char* key : {"radius_min", "radius_max"})
      if (r.has(key)) r.fail(key, "not used with size.distribution = \"sieve\": the curve's first and last diameters bound the sizes");
    g.radius_min = 0.5 * g.size.sieve.front().first;
    g.radius_max = 0.5 * g.size.sieve.back().first;
  } else {
    g.radius_min = r.number("radius_min", 0, kInf, "m", true);
    g.radius_max = r.number("radius_max", 0, kInf, "m", true);
    if (g.radius_min > g.radius_max) r.fail("radius_max", "radius_max must be >= radius_min (" + std::to_string(g.radius_min) + " m)");
    const double mass = truncated_mass(g.size, g.radius_min, g.radius_max);
    if (!(mass >= kMinTruncatedMass)) {
      std::ostringstream m;
      m << "only a fraction " << mass << " of the distribution lies in [radius_min, radius_max] = [" << g.radius_min << ", " << g.radius_max
        << "] m (at least " << kMinTruncatedMass << " is needed): move the distribution or the bounds";
      r.fail("size", m.str());
    }
  }
  const Vec3 centre = 0.5 * (lo + hi);
  if (!sphere_in_region(g.region, centre, g.radius_max) && g.region.kind != Region::Kind::Mesh)
    r.fail("region", "a sphere of the largest radius (" + std::to_string(g.radius_max) + " m) does not fit in the region");
  // The rate: exactly one of a count and a mass per second.
  const bool by_count = r.has("count_rate"), by_mass = r.has("mass_rate");
  if (by_count == by_mass) r.fail(by_count ? "mass_rate" : "count_rate", "give exactly one of count_rate [1/s] and mass_rate [kg/s]");
  g.rate_kind = by_mass ? InsertSpec::Rate::Mass : InsertSpec::Rate::Count;
  g.rate = by_mass ? r.number("mass_rate", 0, kInf, "kg/s", true) : r.number("count_rate", 0, kInf, "1/s", true);
  g.velocity = r.vec3_or("velocity", Vec3::Zero());
  g.start = r.number_or("start", 0.0, 0, duration, "s since the stage start", false, true);
  g.end = r.number_or("end", kInf, 0, kInf, "s since the stage start", true);
  if (r.has("end") && !(g.end > g.start)) r.fail("end", "end must be after start (" + std::to_string(g.start) + " s)");
  const bool cap_count = r.has("total_count"), cap_mass = r.has("total_mass");
  if (cap_count && cap_mass) r.fail("total_mass", "give at most one of total_count and total_mass");
  g.total = kInf;
  if (cap_count) g.total = static_cast<double>(r.integer("total_count", 1, 1000000000)), g.total_kind = InsertSpec::Rate::Count;
  if (cap_mass) g.total = r.number("total_mass", 0, kInf, "kg", true), g.total_kind = InsertSpec::Rate::Mass;
  if (cap_count != (g.rate_kind == InsertSpec::Rate::Count) && (cap_count || cap_mass))
    r.fail(cap_count ? "total_count" : "total_mass", by_mass ? "with mass_rate the cap is total_mass [kg]" : "with count_rate the cap is total_count");
  g.seed = static_cast<std::uint64_t>(r.integer_or("seed", 1, 0, std::numeric_limits<long>::max()));
  g.every = r.integer_or("every", 1, 1, 1000000000);
  g.attempts = static_cast<int>(r.integer_or("attempts", 100, 1, 1000000));
  return g;
}

// The group of a [[stage.set_velocity]] or [[stage.prescribe]] entry: material, ids = [first,
// last] and region (with inside), at least one of the three.
ParticleGroupSpec read_particle_group(TableReader& r, const Scene& sc) {
  ParticleGroupSpec g;
  if (r.has("material")) g.material = material_ref(r, "material", sc.materials);
  if (const toml::node* n = r.node("ids")) {
    const toml::array* a = n->as_array();
    if (!a || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer())
      r.fail_at(n, "ids", "expected an array of two integers [first, last] (ids first to last, both included)");
    g.by_ids = true;
    g.id_first = *a->get(0)->value<int64_t>();
    g.id_last = *a->get(1)->value<int64_t>();
    if (g.id_first < 0 || g.id_last < g.id_first)
      r.fail_at(n, "ids", "expected 0 <= first <= last (particle ids are non-negative)");
  }
  if (r.has("region")) g.region = read_region(r, "region");
  g.inside = r.boolean_or("inside", true);
  if (r.has("inside") && !g.region) r.fail("inside", "inside applies to a region: give region too");
  if (g.material < 0 && !g.by_ids && !g.region)
    r.fail_at(nullptr, "material", "choose the particles: give at least one of material = \"name\", ids = [first, last], region = {...}");
  return g;
}

VelocitySpec read_velocity_entry(TableReader& r, const Scene& sc) {
  VelocitySpec v;
  v.group = read_particle_group(r, sc);
  v.velocity = r.vec3("velocity");
  if (r.has("angular_velocity")) v.angular_velocity = r.vec3("angular_velocity");
  return v;
}

// [stage.fluid]: the fluid's properties, its pressure field and the void-fraction kernel
// (forces/fluid.hpp; docs/scene.md). Keys of the other flow are refused by name.
FluidParams read_fluid(TableReader& r) {
  FluidParams f;
  const std::string flow = r.choice("flow", {"uniform", "well"});
  f.viscosity = r.number("viscosity", 0, kInf, "Pa s", true);
  if (f.viscosity > 100 || f.viscosity < 1e-6)
    r.warn("viscosity", num(f.viscosity) + " Pa s is no liquid's or gas's (water 1.0e-3, light oil about 5e-3 Pa s): check the unit");
  f.density = r.number("density", 0, kInf, "kg/m^3", true);
  f.void_cutoff = r.number("void_cutoff", 0, kInf, "m (the void-fraction kernel's support radius; about 3 mean diameters)", true);
  f.void_every = r.integer_or("void_every", f.void_every, 1, 1000000000);
  const char* uniform_keys[] = {"pressure_gradient"};
  const char* well_keys[] = {"well_centre", "well_axis", "well_radius", "drainage_radius", "drawdown"};
  if (flow == "uniform") {
    f.flow = FluidParams::Flow::Uniform;
    for (const char* k : well_keys)
      if (r.has(k)) r.fail(k, "belongs to flow = \"well\" (this fluid's flow is \"uniform\": give pressure_gradient only)");
    f.gradient = r.vec3("pressure_gradient");
    if (!f.gradient.allFinite()) r.fail("pressure_gradient", "must be finite (Pa/m)");
  } else {
    f.flow = FluidParams::Flow::Well;
    for (const char* k : uniform_keys)
      if (r.has(k)) r.fail(k, "belongs to flow = \"uniform\" (this fluid's flow is \"well\")");
    f.well_centre = r.vec3("well_centre");
    f.well_axis = direction_or(r, "well_axis", f.well_axis).normalized();
    f.well_radius = r.number("well_radius", 0, kInf, "m", true);
    f.drainage_radius = r.number("drainage_radius", 0, kInf, "m", true);
    if (!(f.drainage_radius > f.well_radius))
      r.fail("drainage_radius", "must exceed well_radius (" + num(f.well_radius) + " m): the pressure is fixed at both radii");
    f.drawdown = r.number("drawdown", -kInf, kInf, "Pa (reservoir minus well pressure; > 0: flow into the well)", true, true);
  }
  return f;
}

// [stage.fibres] (generation/fibre_placement.hpp): how many, how long, and the fibre's material.
FibreSpec read_fibres(TableReader& r) {
  FibreSpec f;
  if (r.has("count") == r.has("volume_fraction"))
    r.fail_at(nullptr, "count", "give exactly one of count (fibres) and volume_fraction (fibre volume / sample volume)");
  if (r.has("count")) f.count = r.integer("count", 1, 100000000);
  else f.volume_fraction = r.number("volume_fraction", 0, 0.5, "(fibre volume / the particles' bounding box)", true);
  if (r.has("length") == (r.has("length_min") || r.has("length_max")))
    r.fail_at(nullptr, "length", "give either length (one length) or both length_min and length_max (drawn uniformly) [m]");
  if (r.has("length")) {
    f.length_min = f.length_max = r.number("length", 0, kInf, "m", true);
  } else {
    f.length_min = r.number("length_min", 0, kInf, "m", true);
    f.length_max = r.number("length_max", f.length_min, kInf, "m (at least length_min)");
  }
  f.diameter = r.number("diameter", 0, kInf, "m", true);
  f.youngs_modulus = r.number("youngs_modulus", 0, kInf, "Pa", true);
  f.tensile_strength = r.number("tensile_strength", 0, kInf, "Pa", true);
  f.seed = static_cast<std::uint64_t>(r.integer_or("seed", 1, 0, std::numeric_limits<long>::max()));
  r.finish();
  return f;
}

void read_stages(TableReader& top, Scene& sc) {
  const auto list = top.tables("stage");
  for (std::size_t k = 0; k < list.size(); ++k) {
    TableReader r(*list[k], top.file(), indexed("stage", k));
    StageSpec s;
    s.name = r.string("name");
    if (s.name.empty() || s.name.find_first_of("/\\ ") != std::string::npos) r.fail("name", "a stage name must be non-empty without '/', '\\' or spaces");
    if (sc.stage(s.name)) r.fail("name", "duplicate stage name");
    s.duration = r.number("duration", 0, kInf, "s", true);
    s.output_every = r.interval_or("output_every", {}, true, "s (0 = first and last frame only)");
    if (r.has("gravity")) {
      s.gravity = r.vec3("gravity");
      check_gravity(r, *s.gravity);
    }
    s.health_every = r.interval_or("health_every", {}, true, "s (0 or absent = a hundredth of the stage, at least 500 steps)");
    s.energy_every = r.interval_or("energy_every", {}, false, "s (absent = no energy log)");
    const auto actions = r.tables("action");
    for (std::size_t a = 0; a < actions.size(); ++a) {
      TableReader ar(*actions[a], top.file(), r.name(indexed("action", a)));
      ActionSpec act;
      const std::string type = ar.choice("type", {"remove", "reset_reference", "bond", "fix", "release"});
      if (type == "remove" || type == "fix") {
        act.kind = type == "remove" ? ActionSpec::Kind::Remove : ActionSpec::Kind::Fix;
        act.region = read_region(ar, "region");
        act.inside = ar.boolean_or("inside", true);
      } else if (type == "release") {
        act.kind = ActionSpec::Kind::Release;
        if (ar.has("region")) act.region = read_region(ar, "region");
        act.inside = ar.boolean_or("inside", true);
      } else if (type == "bond") {
        act.kind = ActionSpec::Kind::Bond;
        act.walls = ar.boolean_or("walls", false);
        act.gap = ar.number_or("gap", act.gap, 0, 1, "(fraction of the smaller radius)", false, true);
      } else {
        act.kind = ActionSpec::Kind::ResetReference;
      }
      ar.finish();
      s.actions.push_back(act);
    }
    const auto motions = r.tables("motion");
    for (std::size_t m = 0; m < motions.size(); ++m) {
      TableReader mr(*motions[m], top.file(), r.name(indexed("motion", m)));
      MotionSpec ms;
      ms.wall = wall_ref(mr, sc);
      read_motion(mr, ms);
      mr.finish();
      s.motions.push_back(ms);
    }
    const auto servos = r.tables("servo");
    for (std::size_t m = 0; m < servos.size(); ++m) {
      TableReader sr(*servos[m], top.file(), r.name(indexed("servo", m)));
      ServoSpec sv;
      sv.wall = wall_ref(sr, sc);
      const toml::node& wn = *sr.node("wall");
      for (const WallSpec& w : sc.walls) {
        if (!wall_matches(w.name, sv.wall)) continue;
        WallMotion m;
        for (const MotionSpec& ms : s.motions)
          if (wall_matches(w.name, ms.wall)) ms.apply_to(m);
        if (m.moves())
          sr.fail_at(&wn, "wall", "wall \"" + w.name + "\" also moves by [[stage.motion]]: a servo wall only translates under its servo " +
                                      "(add a motion of type \"fixed\" for it after the others)");
      }
      for (const ServoSpec& o : s.servos)
        for (const WallSpec& w : sc.walls)
          if (wall_matches(w.name, sv.wall) && wall_matches(w.name, o.wall))
            sr.fail_at(&wn, "wall", "wall \"" + w.name + "\" is already in servo \"" + o.wall + "\"");
      sv.target_stress = sr.number("target_stress", 0, kInf, "Pa", true);
      sv.max_speed = sr.number("max_speed", 0, kInf, "m/s", true);
      sv.gain = sr.number_or("gain", sv.gain, 0, 1, "(dimensionless)", true);
      sv.integral_time = sr.number_or("integral_time", sv.integral_time, 0, kInf, "s");
      if (sr.has("direction")) sv.direction = unit_direction(sr, "direction");
      sr.finish();
      s.servos.push_back(sv);
    }
    const auto inserts = r.tables("insert");
    for (std::size_t m = 0; m < inserts.size(); ++m) {
      TableReader ir(*inserts[m], top.file(), r.name(indexed("insert", m)));
      s.inserts.push_back(read_insert(ir, sc, s.duration));
      ir.finish();
    }
    for (const char* key : {"set_velocity", "prescribe"}) {
      const auto entries = r.tables(key);
      for (std::size_t m = 0; m < entries.size(); ++m) {
        TableReader vr(*entries[m], top.file(), r.name(indexed(key, m)));
        (std::string(key) == "prescribe" ? s.prescribes : s.set_velocities).push_back(read_velocity_entry(vr, sc));
        vr.finish();
      }
    }
    if (const toml::table* t = r.subtable("fluid")) {
      TableReader fr(*t, top.file(), r.name("fluid"));
      s.fluid = read_fluid(fr);
      fr.finish();
    }
    if (const toml::table* t = r.subtable("sink")) {
      TableReader kr(*t, top.file(), r.name("sink"));
      SinkSpec sink;
      sink.region = read_region(kr, "region");
      sink.every = kr.integer_or("every", sink.every, 1, 1000000000);
      kr.finish();
      s.sink = sink;
    }
    if (const toml::table* ft = r.subtable("fibres")) {
      TableReader fr(*ft, top.file(), r.name("fibres"));
      s.fibres = read_fibres(fr);
    }
    r.finish();
    sc.stages.push_back(std::move(s));
  }
}

}  // namespace

bool same_scene_values(const std::string& a, const std::string& b) {
  try {
    const toml::table ta = toml::parse(a), tb = toml::parse(b);
    // Equal values, and written out alike (the == of numbers takes -0 for 0 and 1 for 1.0).
    std::ostringstream sa, sb;
    sa << ta, sb << tb;
    return ta == tb && sa.str() == sb.str();
  } catch (const toml::parse_error&) {
    return false;
  }
}

Scene parse_scene(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << path << ':' << e.source().begin.line << ':' << e.source().begin.column << ": TOML syntax error: " << e.description();
    throw InputError(s.str());
  }
  Scene sc;
  sc.path = path;
  sc.text = text;
  files_read = &sc.files;
  warnings_out = &sc.warnings;
  struct Reset {
    ~Reset() { files_read = nullptr, warnings_out = nullptr; }
  } reset;
  TableReader top(root, path, "");
  read_simulation(top, sc);
  read_materials(top, sc);
  read_walls(top, sc);
  read_generation(top, sc);
  read_copy(top, sc);
  read_compact(top, sc);
  read_stages(top, sc);
  top.finish();
  return sc;
}

Scene read_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the scene file");
  std::ostringstream s;
  s << in.rdbuf();
  return parse_scene(s.str(), path);
}

}  // namespace dem
