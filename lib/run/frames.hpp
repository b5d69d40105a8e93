#pragma once
// VTK frames of a stage: <dir>/<stage>/particles_NNNNNN.vtu and walls_NNNNNN.vtp, listed in
// <dir>/<stage>_particles.pvd and <dir>/<stage>_walls.pvd for ParaView's time series.
//
// While the stage runs the frames go to <dir>/<stage>.partial/ (the same layout, so its .pvd opens
// in ParaView); commit() moves them into place when the stage completes, replacing the series there
// whole. So <dir> never holds the frames of a failed run, nor a mix of two runs (an earlier, longer
// run's last frames are removed). Only the files of this stage's series are touched.
#include <cstddef>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace dem {

class FrameWriter {
 public:
  FrameWriter(std::string dir, std::string stage);
  // Writes frame number times.size() - 1 at the current state and rewrites both .pvd files.
  void write(const Simulation& sim, const std::vector<double>& times) const;
  // Removes the staged frames (an earlier run's left over, or this failed run's).
  void discard() const;
  // Moves the staged series of `frames` frames into place and removes the stale frames of the series.
  void commit(std::size_t frames) const;

 private:
  std::string dir_, stage_, staging_;
};

}  // namespace dem
