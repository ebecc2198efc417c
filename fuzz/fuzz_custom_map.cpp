// Custom maps: nav::parse_custom_map on the input text. CustomMapError is its documented failure.
// The header also promises parse(format(m)) == m: a map that reads must read back the same after
// formatting, and a difference is a finding too.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "nav/common/custom_map.hpp"

namespace nav = neopipe::nav;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nav::CustomMap map;
  try {
    map = nav::parse_custom_map(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const nav::CustomMapError&) {
    return 0;
  }
  if (nav::parse_custom_map(nav::format_custom_map(map)) != map) std::abort();
  return 0;
}
