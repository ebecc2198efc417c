#include "pipeline/io/files.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "pipeline/io/frame_source.hpp"

namespace neopipe::pipeline::io {

std::string size_text(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

void require_readable(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SourceError(path + ": cannot open: " + std::strerror(errno));
}

}  // namespace neopipe::pipeline::io
