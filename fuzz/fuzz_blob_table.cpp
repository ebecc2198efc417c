// Blob tables read by `neopipe map --blobs`: mapmaker::read_blob_positions on the input bytes
// written to a file, then the workspace check the command makes next. MapError is the documented
// failure of both.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.hpp"
#include "nav/mapmaker/workspace.hpp"

namespace mm = neopipe::nav::mapmaker;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static neopipe::fuzz::InputFile file;
  try {
    const std::string& path = file.write(data, size);
    mm::check_workspace(mm::Workspace{{500, 500}, mm::read_blob_positions(path)}, path);
  } catch (const mm::MapError&) {
  }
  return 0;
}
