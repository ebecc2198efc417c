// Point-pair files (`neopipe calibrate --points`): calib::read_points_csv on the input bytes written
// to a file. CalibrationError is its documented failure.

#include <cstddef>
#include <cstdint>

#include "calib/points_csv.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  try {
    (void)neopipe::calib::read_points_csv(file.write(data, size));
  } catch (const neopipe::calib::CalibrationError&) {
  }
  return 0;
}
