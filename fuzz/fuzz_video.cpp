// The FFmpeg-backed video reader: LibavVideoSource on the input bytes written to a file (FFmpeg
// probes the format from the content; the file has no extension to go by), reading a few frames.
// SourceError is its documented failure. The input's length picks gray or BGR output, so both of
// the converter's paths run without spending input bytes on the choice.
//
// FFmpeg itself is not instrumented: a fault inside it shows only if it crashes outright.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "pipeline/io/libav_video_source.hpp"

namespace io = neopipe::pipeline::io;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  constexpr int kFrames = 4;  // enough to pass the first (decoded at open) and meet a size change
  try {
    io::LibavVideoSource video(file.write(data, size), size % 2 == 0 ? io::ColorFormat::gray : io::ColorFormat::bgr);
    (void)video.fps();
    (void)video.frame_count();
    for (int i = 0; i < kFrames && video.next(); ++i) {
    }
  } catch (const io::SourceError&) {
  }
  return 0;
}
