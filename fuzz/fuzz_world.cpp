// World files: sim::load_world on the input bytes written to a file (it takes only a path).
// WorldError is its documented failure.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "sim/world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  try {
    (void)neopipe::sim::load_world(file.write(data, size));
  } catch (const neopipe::sim::WorldError&) {
  }
  return 0;
}
