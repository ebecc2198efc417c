#include "pipeline/value.hpp"

#include <array>
#include <utility>

namespace neopipe::pipeline {
namespace {
constexpr std::array<std::pair<PortType, std::string_view>, 5> kNames{{{PortType::bgr8, "bgr8"},
                                                                       {PortType::gray8, "gray8"},
                                                                       {PortType::s16, "s16"},
                                                                       {PortType::histogram, "histogram"},
                                                                       {PortType::blobs, "blobs"}}};
}

std::string_view to_string(PortType t) {
  for (const auto& [type, name] : kNames) {
    if (type == t) return name;
  }
  return "?";
}

std::optional<PortType> port_type_from_string(std::string_view name) {
  for (const auto& [type, n] : kNames) {
    if (n == name) return type;
  }
  return std::nullopt;
}

bool is_image(PortType t) {
  return cv_type(t) >= 0;
}

int cv_type(PortType t) {
  switch (t) {
    case PortType::bgr8:
      return CV_8UC3;
    case PortType::gray8:
      return CV_8UC1;
    case PortType::s16:
      return CV_16SC1;
    case PortType::histogram:
    case PortType::blobs:
      return -1;
  }
  return -1;
}

Value constant_value(PortType t, cv::Size size, int fill) {
  switch (t) {
    case PortType::histogram: {
      Histogram h{};
      h.fill(static_cast<std::uint64_t>(fill));
      return h;
    }
    case PortType::blobs:
      return BlobList{};
    default:
      return cv::Mat(size, cv_type(t), cv::Scalar::all(fill));
  }
}

}  // namespace neopipe::pipeline
