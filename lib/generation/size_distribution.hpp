#pragma once
// Particle size distributions for generation (`[generation.size]`, docs/scene.md): uniform,
// truncated normal and log-normal radii, and sieve curves of cumulative mass fraction passing.
// The sampler needs only an rng, so any placement (gen-primary, insertion over time) can use it.
#include <random>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace dem {

// The least fraction of an untruncated normal or log-normal distribution that must lie within
// [radius_min, radius_max]; below it the truncated draw is a spike at one bound, not the curve asked.
inline constexpr double kMinTruncatedMass = 1e-3;

// Fraction of the untruncated normal or log-normal distribution of `spec` within [r_min, r_max]
// (1 for uniform and sieve).
double truncated_mass(const SizeSpec& spec, double r_min, double r_max);

// Draws radii of one distribution in [r_min, r_max], one uniform variate of the rng per radius
// (by the inverse of the number distribution's CDF), so a seed fixes every radius.
class RadiusSampler {
 public:
  // Throws InputError when truncated_mass < kMinTruncatedMass or a sieve curve is malformed.
  RadiusSampler(const SizeSpec& spec, double r_min, double r_max);

  // The radius at which the number CDF reaches u in [0, 1].
  double quantile(double u) const;
  double draw(std::mt19937_64& rng) const;
  std::vector<double> draw(std::size_t n, std::mt19937_64& rng) const;

  // Mean and standard deviation of the radius under the truncated distribution (not for sieve).
  double mean() const;
  double stddev() const;

  const SizeSpec& spec() const { return spec_; }
  double r_min() const { return r_min_; }
  double r_max() const { return r_max_; }

 private:
  double sieve_quantile(double u) const;

  SizeSpec spec_;
  double r_min_, r_max_;
  double z_lo_ = 0, z_hi_ = 0;          // truncation bounds in standard-normal units (normal, log-normal)
  double cdf_lo_ = 0, cdf_hi_ = 0;      // Phi at those bounds
  std::vector<double> sieve_cumulative_;  // number fraction below each sieve diameter
};

// One line of a size report: a quantity of the distribution asked and of the radii drawn.
struct SizeCheck {
  std::string what;
  double diameter = 0;  // the sieve's diameter [m] (sieve rows; 0 otherwise)
  double asked = 0, realised = 0;
};

// What the radii drawn show against the distribution: mean, standard deviation and median of the
// radius (uniform, normal, log-normal), or the mass fraction passing each sieve diameter (sieve).
std::vector<SizeCheck> size_report(const RadiusSampler& sampler, const std::vector<double>& radii);

// Mass fraction of the spheres with diameter below d (sphere mass taken as r^3: one density).
double mass_fraction_below(const std::vector<double>& radii, double d);

// Name of a distribution as in the scene file ("uniform", "normal", "lognormal", "sieve").
const char* size_kind_name(SizeSpec::Kind k);

}  // namespace dem
