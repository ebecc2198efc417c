#pragma once
// The picture of `neopipe compare --plot`: per system its goal rate with the 95 % interval, and the
// median path it travelled against the straight line.

#include <string>

#include "rig/comparison.hpp"

namespace neopipe::apps {

/// Writes a PNG. Throws std::runtime_error when the file cannot be written.
void write_compare_plot(const rig::Comparison& comparison, const std::string& path);

}  // namespace neopipe::apps
