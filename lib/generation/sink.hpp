#pragma once
// A sink (`[stage.sink]`, docs/scene.md): particles whose centre lies in a region at a sink event
// are removed and counted, with their mass; the sand a well produces (workflows/sand-production).
// What an event removes depends only on the positions, so the running totals are all a restart
// needs: they are kept in the checkpoint (/run/sink_count, /run/sink_mass).
#include <cstddef>
#include <cstdint>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// What a sink has removed since the stage start.
struct SinkTotals {
  std::int64_t count = 0;
  double mass = 0;  // [kg], summed event by event, within an event in id order (the same bits on any thread count)
};

// One sink event when (stage_step % spec.every) == 0: every particle whose centre is in the region
// is removed with its contacts and added to `totals`. Returns how many were removed (0: nothing
// changed).
std::size_t sink_due(Simulation& sim, const SinkSpec& spec, std::int64_t stage_step, SinkTotals& totals);

}  // namespace dem
