#pragma once
// Small helpers for messages about files.

#include <opencv2/core/types.hpp>
#include <string>

namespace neopipe::pipeline::io {

/// "WxH".
std::string size_text(cv::Size s);
/// Throws SourceError "PATH: cannot open: REASON" when `path` cannot be opened for reading.
void require_readable(const std::string& path);

}  // namespace neopipe::pipeline::io
