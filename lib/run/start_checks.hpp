#pragma once
// What is likely wrong with a run, checked once at its start and never during a step
// (docs/scene.md, "Warnings"): the generation box crossed by a wall, particles overlapping walls or
// each other at step 0, walls that move faster than the contacts can follow. Each finding is a
// warning on stderr before the run; a run that then blows up (PhysicsError) lists the findings,
// most likely first, before the core's time-step and stiffness advice, which applies when none does.
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The thresholds of the findings (docs/scene.md, "Warnings").
inline constexpr double kStartOverlapShare = 0.2;  // an overlap at step 0 above this share of simulation.max_overlap
inline constexpr double kWallStepRadii = 0.1;      // a wall moving more than this many smallest radii per step

struct Suspect {
  double score = 0;  // the measure over its warning threshold (> 1): the larger, the likelier the cause
  std::string text;
};

class StartChecks {
 public:
  // The checks on `sim` as it starts: particles placed, walls with their motions, dt chosen.
  // `generation`: gen-primary's box, checked against the walls. Costs one force evaluation on a copy.
  explicit StartChecks(const Simulation& sim, const GenerationSpec* generation = nullptr);

  const std::vector<Suspect>& suspects() const { return suspects_; }  // most likely first
  const std::vector<std::string>& slow() const { return slow_; }      // costly settings, not causes of failure
  void print(const std::string& tool) const;                          // "TOOL: warning: ..." on stderr

  // Rethrows e with the suspects listed before its advice (e unchanged when there are none).
  [[noreturn]] void rethrow(const PhysicsError& e) const;
  // Runs f; a PhysicsError from it comes back through rethrow.
  template <class F>
  decltype(auto) guard(F&& f) const {
    try {
      return f();
    } catch (const PhysicsError& e) {
      rethrow(e);
    }
  }

 private:
  std::vector<Suspect> suspects_;
  std::vector<std::string> slow_;
};

// The fluid's drag relaxes a grain's velocity towards the flow's in tau = rho_p / (d(D w)/dw)
// (docs/physics.md P76, D = beta / (1 - eps) of P72 at the slip speed w); the explicit step is
// stable below 2 tau (P77). The grain of the shortest tau at the stage start, with its void
// fraction (computed here) and slip.
struct DragRelaxation {
  double tau = std::numeric_limits<double>::infinity();  // [s]
  long slot = -1;
  double eps = 0, slip = 0;
};
DragRelaxation shortest_drag_relaxation(const Simulation& sim);
// Throws InputError when sim.dt > 2 tau of the stage's fluid (P77), naming the grain, its size and
// the limit; `forced` (simulation.force_time_step): a warning on stderr instead. No fluid: nothing.
void check_drag_step(const Simulation& sim, bool forced, const std::string& stage);

// The scene's plausibility warnings (Scene::warnings) as "TOOL: warning: ..." on stderr.
void print_scene_warnings(const Scene& scene, const std::string& tool);

}  // namespace dem
