// The image-signature sniffer that tells images from videos for `neopipe run`: has_image_signature
// on the input bytes, and file_has_image_signature on them written to a file. Neither throws; any
// crash or sanitizer report is a finding. The two must agree on the first 132 bytes.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fuzz/fuzz_support.hpp"
#include "pipeline/io/image_signature.hpp"

namespace io = neopipe::pipeline::io;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  const std::string_view head(reinterpret_cast<const char*>(data), std::min<std::size_t>(size, 132));
  if (io::has_image_signature(head) != io::file_has_image_signature(file.write(data, size))) std::abort();
  return 0;
}
