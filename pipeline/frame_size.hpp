#pragma once
// How error messages name a frame's size: "640x480".

#include <opencv2/core/types.hpp>
#include <string>

namespace neopipe::pipeline {

inline std::string size_text(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

}  // namespace neopipe::pipeline
