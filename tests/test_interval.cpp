// Intervals in steps or seconds (core/interval.hpp): what the text means and the steps it gives.
#include <gtest/gtest.h>

#include <string>

#include "core/interval.hpp"

namespace dem {
namespace {

Interval parsed(const char* text, Interval::Unit bare, bool zero_ok = false) {
  std::string why;
  const std::optional<Interval> r = parse_interval(text, bare, zero_ok, why);
  EXPECT_TRUE(r) << text << ": " << why;
  return r.value_or(Interval{});
}

TEST(Interval, ABareNumberTakesTheUnitOfItsPlace) {
  EXPECT_EQ(parsed("400", Interval::Unit::Steps).steps(1e-5), 400);
  EXPECT_EQ(parsed("0.004", Interval::Unit::Seconds).steps(1e-5), 400);
}

TEST(Interval, AUnitOverridesIt) {
  for (const char* text : {"0.004 s", "0.004s", " 4e-3 s "}) {
    const Interval i = parsed(text, Interval::Unit::Steps);
    EXPECT_EQ(i.unit, Interval::Unit::Seconds) << text;
    EXPECT_EQ(i.steps(1e-5), 400) << text;
  }
  for (const char* text : {"400 steps", "400steps", "1 step"}) EXPECT_EQ(parsed(text, Interval::Unit::Seconds).unit, Interval::Unit::Steps) << text;
}

// Seconds round to the nearest whole step, never below one: 0.00401 s at 1e-5 s is 401 steps, and
// a time shorter than a step is every step.
TEST(Interval, SecondsRoundToWholeStepsAtLeastOne) {
  EXPECT_EQ(seconds(0.004011).steps(1e-5), 401);
  EXPECT_EQ(seconds(1e-9).steps(1e-5), 1);
  EXPECT_EQ(Interval{}.steps(1e-5), 0) << "not given";
}

TEST(Interval, BadTextIsRefusedWithTheReason) {
  const struct {
    const char* text;
    bool zero_ok;
    const char* why;
  } cases[] = {{"often", false, "expected steps or seconds"}, {"10 ms", false, "expected steps or seconds"},
               {"2.5", false, "whole number of steps"},      {"2.5 steps", false, "whole number of steps"},
               {"0", false, "must be > 0"},                  {"-1 s", true, "must be >= 0"},
               {"", false, "expected steps or seconds"},             {"inf s", false, "expected steps or seconds"}};
  for (const auto& c : cases) {
    std::string why;
    EXPECT_FALSE(parse_interval(c.text, Interval::Unit::Steps, c.zero_ok, why)) << c.text;
    EXPECT_NE(why.find(c.why), std::string::npos) << c.text << ": " << why;
  }
  std::string why;
  EXPECT_TRUE(parse_interval("0", Interval::Unit::Steps, true, why)) << "0 = off where allowed";
}

}  // namespace
}  // namespace dem
