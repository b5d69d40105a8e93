// libFuzzer target: the checkpoint reader must reject any damaged file with an IoError, never
// crash or read out of bounds. Inputs are whole files; seed it with real checkpoints
// (fuzz/seed.sh writes them).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "io/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/dem_fuzz_checkpoint_" + std::to_string(::getpid()) + ".h5";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  dem::Simulation sim;
  dem::CheckpointMeta meta;
  try {
    dem::read_checkpoint(path, sim, meta);
  } catch (const dem::IoError&) {
  }
  return 0;
}
