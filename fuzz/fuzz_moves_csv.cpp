// Moves files (`neopipe sim arm --moves`): sim::MovesReader over the input bytes written to a file,
// to the end or to the first bad line. MovesError is its documented failure.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "sim/arm/moves_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  try {
    neopipe::sim::MovesReader reader(file.write(data, size));
    while (reader.next()) {
    }
  } catch (const neopipe::sim::MovesError&) {
  }
  return 0;
}
