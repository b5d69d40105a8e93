#include "generation/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace dem {

namespace {

double phi(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi); }
double Phi(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

bool is_gaussian(SizeSpec::Kind k) { return k == SizeSpec::Kind::Normal || k == SizeSpec::Kind::LogNormal; }

// Radius r in standard-normal units of the untruncated distribution, and back.
double to_z(const SizeSpec& s, double r) {
  return s.kind == SizeSpec::Kind::Normal ? (r - s.mean_radius) / s.std_radius : std::log(r / s.median_radius) / std::log(s.geometric_std);
}
double from_z(const SizeSpec& s, double z) {
  return s.kind == SizeSpec::Kind::Normal ? s.mean_radius + s.std_radius * z : s.median_radius * std::exp(std::log(s.geometric_std) * z);
}

// z in [lo, hi] with Phi(z) = target, by bisection: always terminates (200 halvings at most, far
// below a double's spacing in r), needs no approximation of the inverse.
double inverse_Phi(double target, double lo, double hi) {
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // lo and hi are adjacent doubles
    (Phi(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Number weight of sieve interval [a, b] holding mass fraction dF, the mass spread evenly over
// ln d (the curve interpolated on a log axis): n(d) ~ dF / (ln(b/a) d^4), integrated over [a, b].
double sieve_weight(double a, double b, double dF) { return dF / std::log(b / a) * (std::pow(a, -3) - std::pow(b, -3)) / 3; }

// Mean and variance of a sample (population formulas), summed about x[0] so that equal radii
// give a variance of exactly 0.
std::pair<double, double> mean_variance(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size()), x0 = x[0];
  double m = 0;
  for (double v : x) m += v - x0;
  m /= n;
  double var = 0;
  for (double v : x) var += (v - x0 - m) * (v - x0 - m);
  return {x0 + m, var / n};
}

double sample_median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

}  // namespace

const char* size_kind_name(SizeSpec::Kind k) {
  switch (k) {
    case SizeSpec::Kind::Normal: return "normal";
    case SizeSpec::Kind::LogNormal: return "lognormal";
    case SizeSpec::Kind::Sieve: return "sieve";
    default: return "uniform";
  }
}

double truncated_mass(const SizeSpec& spec, double r_min, double r_max) {
  if (!is_gaussian(spec.kind)) return 1;
  return Phi(to_z(spec, r_max)) - Phi(to_z(spec, r_min));
}

RadiusSampler::RadiusSampler(const SizeSpec& spec, double r_min, double r_max) : spec_(spec), r_min_(r_min), r_max_(r_max) {
  if (is_gaussian(spec.kind)) {
    const double mass = truncated_mass(spec, r_min, r_max);
    if (!(mass >= kMinTruncatedMass)) {
      std::ostringstream m;
      m << "generation.size: only " << mass << " of the " << size_kind_name(spec.kind) << " distribution lies in [radius_min, radius_max] = ["
        << r_min << ", " << r_max << "] m (at least " << kMinTruncatedMass << " is needed)";
      throw InputError(m.str());
    }
    z_lo_ = to_z(spec, r_min);
    z_hi_ = to_z(spec, r_max);
    cdf_lo_ = Phi(z_lo_);
    cdf_hi_ = Phi(z_hi_);
  }
  if (spec.kind == SizeSpec::Kind::Sieve) {
    const auto& c = spec.sieve;
    double total = 0;
    sieve_cumulative_.push_back(0);
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      total += sieve_weight(c[k].first, c[k + 1].first, c[k + 1].second - c[k].second);
      sieve_cumulative_.push_back(total);
    }
    if (c.size() < 2 || !(total > 0)) throw InputError("generation.size.sieve: the curve needs two rows and a rising fraction");
    for (double& w : sieve_cumulative_) w /= total;
    sieve_cumulative_.back() = 1;  // u < 1 always falls in a sieve interval
  }
}

double RadiusSampler::quantile(double u) const {
  switch (spec_.kind) {
    case SizeSpec::Kind::Uniform: return r_min_ + (r_max_ - r_min_) * u;  // today's draw, bit for bit
    case SizeSpec::Kind::Sieve: return sieve_quantile(u);
    default: {
      const double z = inverse_Phi(cdf_lo_ + u * (cdf_hi_ - cdf_lo_), z_lo_, z_hi_);
      return std::clamp(from_z(spec_, z), r_min_, r_max_);  // z -> r may round past a bound
    }
  }
}

// Picks the sieve interval by its number weight, then d within it by the inverse of the number
// CDF (d_a^-3 - d^-3) / (d_a^-3 - d_b^-3).
double RadiusSampler::sieve_quantile(double u) const {
  const auto& c = sieve_cumulative_;
  std::size_t k = std::min<std::size_t>(std::upper_bound(c.begin() + 1, c.end(), u) - c.begin() - 1, c.size() - 2);
  while (k > 0 && c[k + 1] == c[k]) --k;  // u = 1 past a flat end: the last interval holding mass
  const double a = spec_.sieve[k].first, b = spec_.sieve[k + 1].first;
  const double v = std::clamp((u - sieve_cumulative_[k]) / (sieve_cumulative_[k + 1] - sieve_cumulative_[k]), 0.0, 1.0);
  const double d = std::pow(std::pow(a, -3) - v * (std::pow(a, -3) - std::pow(b, -3)), -1.0 / 3);
  return std::clamp(0.5 * d, 0.5 * a, 0.5 * b);
}

double RadiusSampler::draw(std::mt19937_64& rng) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  return quantile(unit(rng));
}

std::vector<double> RadiusSampler::draw(std::size_t n, std::mt19937_64& rng) const {
  std::vector<double> r(n);
  for (double& a : r) a = draw(rng);
  return r;
}

double RadiusSampler::mean() const {
  switch (spec_.kind) {
    case SizeSpec::Kind::Uniform: return 0.5 * (r_min_ + r_max_);
    case SizeSpec::Kind::Normal:
      return spec_.mean_radius + spec_.std_radius * (phi(z_lo_) - phi(z_hi_)) / (cdf_hi_ - cdf_lo_);
    case SizeSpec::Kind::LogNormal: {
      // E[r] of a truncated log-normal: median e^{s^2/2} (Phi(b - s) - Phi(a - s)) / (Phi(b) - Phi(a)).
      const double s = std::log(spec_.geometric_std);
      return spec_.median_radius * std::exp(0.5 * s * s) * (Phi(z_hi_ - s) - Phi(z_lo_ - s)) / (cdf_hi_ - cdf_lo_);
    }
    default: return 0;
  }
}

double RadiusSampler::stddev() const {
  const double Z = cdf_hi_ - cdf_lo_;
  switch (spec_.kind) {
    case SizeSpec::Kind::Uniform: return (r_max_ - r_min_) / std::sqrt(12.0);
    case SizeSpec::Kind::Normal: {
      const double m = (phi(z_lo_) - phi(z_hi_)) / Z;
      const double var = 1 + (z_lo_ * phi(z_lo_) - z_hi_ * phi(z_hi_)) / Z - m * m;
      return spec_.std_radius * std::sqrt(var);
    }
    case SizeSpec::Kind::LogNormal: {
      // E[r^2] = median^2 e^{2 s^2} (Phi(b - 2s) - Phi(a - 2s)) / Z, as for the mean.
      const double s = std::log(spec_.geometric_std);
      const double m2 = spec_.median_radius * spec_.median_radius * std::exp(2 * s * s) * (Phi(z_hi_ - 2 * s) - Phi(z_lo_ - 2 * s)) / Z;
      const double m1 = mean();
      return std::sqrt(std::max(0.0, m2 - m1 * m1));
    }
    default: return 0;
  }
}

double mass_fraction_below(const std::vector<double>& radii, double d) {
  double below = 0, all = 0;
  for (double r : radii) {
    const double m = r * r * r;
    all += m;
    if (2 * r < d) below += m;
  }
  return all > 0 ? below / all : 0;
}

std::vector<SizeCheck> size_report(const RadiusSampler& sampler, const std::vector<double>& radii) {
  std::vector<SizeCheck> out;
  if (radii.empty()) return out;
  if (sampler.spec().kind == SizeSpec::Kind::Sieve) {
    for (const auto& [d, F] : sampler.spec().sieve) {
      std::ostringstream what;
      what << "mass fraction passing d = " << d << " m";
      out.push_back({what.str(), d, F, mass_fraction_below(radii, d)});
    }
    return out;
  }
  const auto [m, var] = mean_variance(radii);
  out.push_back({"mean radius [m]", 0, sampler.mean(), m});
  out.push_back({"std of radius [m]", 0, sampler.stddev(), std::sqrt(var)});
  out.push_back({"median radius [m]", 0, sampler.quantile(0.5), sample_median(radii)});
  return out;
}

}  // namespace dem
