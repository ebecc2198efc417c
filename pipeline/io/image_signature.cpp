#include "pipeline/io/image_signature.hpp"

#include <array>
#include <cctype>
#include <fstream>

namespace neopipe::pipeline::io {
namespace {

bool starts_with(std::string_view head, std::string_view magic) {
  return head.substr(0, magic.size()) == magic;
}

bool space_at(std::string_view head, std::size_t i) {
  return head.size() > i && std::isspace(static_cast<unsigned char>(head[i])) != 0;
}

// Netpbm: P1..P6 (PNM), P7 (PAM), PF / Pf (PFM), each followed by white space.
bool netpbm(std::string_view head) {
  if (head.size() < 3 || head[0] != 'P' || !space_at(head, 2)) return false;
  const char kind = head[1];
  return (kind >= '1' && kind <= '7') || kind == 'F' || kind == 'f';
}

}  // namespace

bool has_image_signature(std::string_view head) {
  using namespace std::string_view_literals;
  static constexpr std::array kMagic{
      "\x89PNG\r\n\x1a\n"sv,               // PNG
      "\xff\xd8\xff"sv,                    // JPEG
      "\x00\x00\x00\x0cjP  \r\n\x87\n"sv,  // JPEG 2000 (JP2 box)
      "\xff\x4f\xff\x51"sv,                // JPEG 2000 code stream
      "BM"sv,                              // BMP
      "II\x2a\x00"sv,
      "MM\x00\x2a"sv,  // TIFF
      "II\x2b\x00"sv,
      "MM\x00\x2b"sv,        // BigTIFF
      "\x59\xa6\x6a\x95"sv,  // Sun raster
      "#?RGBE"sv,
      "#?RADIANCE"sv,        // Radiance HDR
      "\x76\x2f\x31\x01"sv,  // OpenEXR
  };
  for (const auto magic : kMagic) {
    if (starts_with(head, magic)) return true;
  }
  if (starts_with(head, "RIFF") && head.size() >= 12 && head.substr(8, 4) == "WEBP") return true;
  if (head.size() >= 132 && head.substr(128, 4) == "DICM") return true;  // DICOM (GDCM)
  return netpbm(head);
}

bool file_has_image_signature(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 132> buf{};
  in.read(buf.data(), buf.size());
  return has_image_signature(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())));
}

}  // namespace neopipe::pipeline::io
