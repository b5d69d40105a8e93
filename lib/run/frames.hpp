#pragma once
// VTK frames of a stage: <dir>/<stage>/particles_NNNNNN.vtu and walls_NNNNNN.vtp, listed in
// <dir>/<stage>_particles.pvd and <dir>/<stage>_walls.pvd for ParaView's time series.
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace dem {

class FrameWriter {
 public:
  FrameWriter(std::string dir, std::string stage) : dir_(std::move(dir)), stage_(std::move(stage)) {}
  // Writes frame number times.size() - 1 at the current state and rewrites both .pvd files.
  void write(const Simulation& sim, const std::vector<double>& times) const;

 private:
  std::string dir_, stage_;
};

}  // namespace dem
