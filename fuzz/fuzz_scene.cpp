// libFuzzer target: the scene parser must accept or reject any text with an InputError, never
// crash, hang or read out of bounds (run under AddressSanitizer and UBSan).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "io/scene_parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    dem::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.toml");
  } catch (const dem::InputError&) {
  }
  return 0;
}
