#pragma once
// An interval between outputs or checks as the user writes it: a whole number of steps or simulated
// seconds, on the command line and in the scene alike (docs/scene.md, "Intervals"). Seconds become
// steps once the stage's time step is known, max(1, round(T / dt)); a resumed run has the same
// time step, so the same steps.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace dem {

struct Interval {
  enum class Unit { Steps, Seconds };
  double value = 0;  // 0 = not given
  Unit unit = Unit::Steps;

  bool given() const { return value > 0; }
  std::int64_t steps(double dt) const {
    if (!given()) return 0;
    return unit == Unit::Steps ? static_cast<std::int64_t>(value) : std::max<std::int64_t>(1, std::llround(value / dt));
  }
};

inline Interval steps(std::int64_t n) { return {static_cast<double>(n), Interval::Unit::Steps}; }
inline Interval seconds(double t) { return {t, Interval::Unit::Seconds}; }

// "400", "400 steps", "1 step", "0.01 s", "0.01s": a number, then optionally a unit; a bare number
// is in `bare`. Steps must be whole; both must be > 0, or = 0 where `zero_ok` (0 = off). On any
// other text returns nothing and says why in `why`.
inline std::optional<Interval> parse_interval(std::string_view text, Interval::Unit bare, bool zero_ok, std::string& why) {
  const auto trim = [](std::string_view s) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    return s;
  };
  text = trim(text);
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const std::string_view unit = trim(text.substr(static_cast<std::size_t>(end - text.data())));
  Interval r{v, bare};
  if (unit == "s") r.unit = Interval::Unit::Seconds;
  else if (unit == "steps" || unit == "step") r.unit = Interval::Unit::Steps;
  if (ec != std::errc() || !std::isfinite(v) || !(unit.empty() || unit == "s" || unit == "steps" || unit == "step")) {
    why = std::string("expected steps or seconds (\"400 steps\", \"0.01 s\"; a bare number counts ") +
          (bare == Interval::Unit::Steps ? "steps" : "seconds") + "), got \"" + std::string(text) + "\"";
    return std::nullopt;
  }
  if (v < 0 || (v == 0 && !zero_ok)) {
    why = std::string("must be ") + (zero_ok ? ">= 0" : "> 0") + ", got " + std::string(text);
    return std::nullopt;
  }
  if (r.unit == Interval::Unit::Steps && (v != std::floor(v) || v > 1e15)) {
    why = "a whole number of steps is allowed, got " + std::string(text);
    return std::nullopt;
  }
  return r;
}

// How an interval reads in messages: "400 steps" or "0.01 s".
inline std::string describe(const Interval& i) {
  if (i.unit == Interval::Unit::Steps) return std::to_string(static_cast<std::int64_t>(i.value)) + " steps";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", i.value);
  return buf;
}

}  // namespace dem
