#include "run/sink_log.hpp"

#include "io/output_paths.hpp"

namespace dem {

std::string sink_path(const std::string& out) { return beside_output(out, ".sink.csv"); }

SinkLog::SinkLog(const std::string& path, std::int64_t resume_step)
    : csv_(path, "step,time_s,removed,removed_total,removed_mass_kg,particles\n", "sink log", resume_step) {}

void SinkLog::record(const Simulation& sim, const SinkTotals& totals, std::size_t removed, bool force) {
  if (!csv_.active() || (removed == 0 && !force)) return;
  std::fprintf(csv_.file(), "%lld,%.12g,%zu,%lld,%.12g,%zu\n", static_cast<long long>(sim.step), sim.time, removed,
               static_cast<long long>(totals.count), totals.mass, sim.particles.size());
  csv_.flush();
}

}  // namespace dem
