#pragma once
// Tells image files from videos by their first bytes, without loading OpenCV's codecs (which live in
// the media plug-in, pipeline/media/media.hpp): `neopipe run VIDEO` must not pay for them.

#include <string>
#include <string_view>

namespace neopipe::pipeline::io {

/// True if `head` (a file's first bytes; 132 are enough) starts as a file of one of the formats
/// OpenCV 4.6's imgcodecs reads: PNG, JPEG, JPEG 2000, BMP, TIFF, WebP, PNM/PAM/PFM, Sun
/// raster, Radiance HDR, OpenEXR, DICOM. Each test is the one the codec's checkSignature makes.
[[nodiscard]] bool has_image_signature(std::string_view head);

/// has_image_signature of the file's first bytes; false if it cannot be read.
[[nodiscard]] bool file_has_image_signature(const std::string& path);

}  // namespace neopipe::pipeline::io
