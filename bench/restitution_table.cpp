// Realised restitution, contact time and peak overlap of binary collisions (bench/binary_collision.hpp)
// against the closed forms of the linear spring and dashpot, worst over pair and wall and eight
// phases of the first touch, at several steps per contact: the tables of docs/contact-laws.md and
// bench/results/restitution.md.
//   restitution_table [steps ...]     (default 16 25 50 100 200 500)
//   restitution_table --hertz [steps ...]   (hertz with Tsuji damping: restitution against eta,
//                                     duration and peak against the same collision at 2000 steps)
//   restitution_table --explicit ...  (either, with the explicit dashpot of docs/contact-laws.md
//                                     eq. D7 in place of D1-D6)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "binary_collision.hpp"

using namespace dem;
using namespace dem::collision;

int main(int argc, char** argv) {
  bool hertz = false, explicit_dashpot = false;
  std::vector<double> steps;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--hertz")) hertz = true;
    else if (!std::strcmp(argv[i], "--explicit")) explicit_dashpot = true;
    else steps.push_back(std::atof(argv[i]));
  }
  if (steps.empty()) steps = {16, 25, 50, 100, 200, 500};
  const double etas[] = {0.05, 0.1, 0.3, 0.5, 0.9, 1.0};
  std::printf("| eta | steps per contact | restitution (worst) | restitution error | contact time error | peak overlap error |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const double eta : etas)
    for (const double n : steps) {
      double worst_e = 0, e_at = eta, worst_t = 0, worst_p = 0;
      for (const bool wall : {false, true}) {
        Shot s;
        s.law = hertz ? NormalLaw::Hertz : NormalLaw::Cundall;
        s.wall = wall;
        s.eta = eta;
        s.explicit_dashpot = explicit_dashpot;
        const double m = effective_mass(wall);
        Closed ref{};
        if (hertz) {
          // The contact time of the elastic impact (test_hertz.cpp) sets the step; the damped
          // collision's duration and peak come from the same collision at 2000 steps.
          const double e_star = 1 / (2 * (1 - s.poisson * s.poisson) / s.young);
          const double r_eff = wall ? kA : kA * kB / (kA + kB);
          const double e_wall = wall ? 1 / ((1 - s.poisson * s.poisson) / s.young * 2) : e_star;
          const double delta = std::pow(15 * m * s.v * s.v / (16 * e_wall * std::sqrt(r_eff)), 0.4);
          s.t_ref = 2.9432751843247047 * delta / s.v;
          Shot f = s;
          f.steps = 2000;
          f.explicit_dashpot = false;  // the more accurate of the two
          const Result fine = collide(f);
          ref = {fine.duration, fine.peak_overlap, eta};
        } else {
          ref = linear_closed_form(s.kn, m, eta, s.v);
          s.t_ref = ref.duration;
        }
        s.steps = n;
        for (int q = 0; q < 8; ++q) {
          s.phase = q / 8.0;
          const Result r = collide(s);
          const double de = (r.restitution - eta) / eta;
          if (std::abs(de) > std::abs(worst_e)) worst_e = de, e_at = r.restitution;
          const double dt_ = (r.duration - ref.duration) / ref.duration, dp = (r.peak_overlap - ref.peak_overlap) / ref.peak_overlap;
          if (std::abs(dt_) > std::abs(worst_t)) worst_t = dt_;
          if (std::abs(dp) > std::abs(worst_p)) worst_p = dp;
        }
      }
      std::printf("| %g | %g | %.5f | %+.3f %% | %+.3f %% | %+.3f %% |\n", eta, n, e_at, 100 * worst_e, 100 * worst_t, 100 * worst_p);
    }
  return 0;
}
