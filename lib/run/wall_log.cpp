#include "run/wall_log.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace dem {

namespace {
constexpr const char* kHeader = "step,time_s,wall,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm,contacts\n";
}

WallLog::WallLog(const std::string& path, const std::vector<Wall>& walls, std::int64_t every, std::int64_t resume_step)
    : path_(path), partial_(path + ".partial"), every_(every > 0 ? every : 1) {
  if (path_.empty()) return;
  for (const Wall& w : walls) {
    // Mesh elements NAME.0, NAME.1, ... make one wall NAME; box faces (box.zmax) are walls of their own.
    const std::size_t dot = w.name.rfind('.');
    const bool element = dot != std::string::npos && dot + 1 < w.name.size() &&
                         w.name.find_first_not_of("0123456789", dot + 1) == std::string::npos;
    const std::string name = element ? w.name.substr(0, dot) : w.name;
    std::size_t g = 0;
    while (g < names_.size() && names_[g] != name) ++g;
    if (g == names_.size()) names_.push_back(name);
    group_of_.push_back(static_cast<int>(g));
  }
  std::string kept = kHeader;
  if (resume_step >= 0) {
    // Keep the rows of the interrupted run up to the checkpoint it resumes from (from the finished
    // file if the run was interrupted after renaming it, before its final checkpoint).
    std::ifstream in(partial_);
    if (!in) in.open(path_);
    std::string line;
    if (std::getline(in, line) && line + "\n" == kHeader)
      while (std::getline(in, line)) {
        char* end = nullptr;
        const long long step = std::strtoll(line.c_str(), &end, 10);
        if (end != line.c_str() && *end == ',' && step <= resume_step) kept += line + "\n";
      }
  }
  file_ = std::fopen(partial_.c_str(), "w");
  if (!file_ || std::fputs(kept.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw IoError(partial_ + ": cannot write the wall force log: " + std::strerror(errno));
}

WallLog::~WallLog() {
  if (file_) std::fclose(file_);
}

void WallLog::record(const Simulation& sim, std::int64_t steps_done, bool last) {
  if (!file_ || (steps_done % every_ != 0 && !last)) return;
  const std::vector<WallLoad> loads = sim.wall_loads(true);
  std::vector<WallLoad> sum(names_.size());
  for (std::size_t e = 0; e < loads.size(); ++e) {
    WallLoad& s = sum[group_of_[e]];
    s.force += loads[e].force;
    s.torque += loads[e].torque;
    s.contacts += loads[e].contacts;
  }
  for (std::size_t g = 0; g < names_.size(); ++g) {
    const WallLoad& s = sum[g];
    std::fprintf(file_, "%lld,%.12g,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d\n", static_cast<long long>(sim.step), sim.time,
                 names_[g].c_str(), s.force.x(), s.force.y(), s.force.z(), s.torque.x(), s.torque.y(), s.torque.z(), s.contacts);
  }
  if (std::fflush(file_) != 0 || std::ferror(file_)) throw IoError(partial_ + ": cannot write the wall force log: " + std::strerror(errno));
}

void WallLog::finish() {
  if (!file_) return;
  const bool bad = std::fclose(file_) != 0;
  file_ = nullptr;
  if (bad || std::rename(partial_.c_str(), path_.c_str()) != 0)
    throw IoError(path_ + ": cannot finish the wall force log: " + std::strerror(errno));
}

}  // namespace dem
