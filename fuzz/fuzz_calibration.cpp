// Calibration files: calib::load_calibration on the input bytes written to a file, then the
// mappings a loaded calibration is used for. CalibrationError is its documented failure.

#include <cstddef>
#include <cstdint>

#include "calib/calibration.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  try {
    const neopipe::calib::Calibration c = neopipe::calib::load_calibration(file.write(data, size));
    // What `neopipe run --calib` and `neopipe calibrate map` do next with a calibration they loaded.
    (void)c.to_world({{0, 0}, {320, 240}});
    (void)c.to_pixel({{0, 0}, {100, 100}});
  } catch (const neopipe::calib::CalibrationError&) {
  }
  return 0;
}
