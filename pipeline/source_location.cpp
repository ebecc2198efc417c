#include "pipeline/source_location.hpp"

namespace neopipe::pipeline {

std::string SourceLocation::str() const {
  std::string s = file.empty() ? std::string("<graph>") : file;
  // Appended piece by piece: `":" + std::to_string(n)` trips GCC 12's -Wrestrict false positive.
  if (line > 0) {
    s.append(":").append(std::to_string(line));
    if (column > 0) s.append(":").append(std::to_string(column));
  }
  return s;
}

GraphError::GraphError(const SourceLocation& where, const std::string& message)
    : std::runtime_error(where.str() + ": " + message), where_(where), message_(message) {}

}  // namespace neopipe::pipeline
