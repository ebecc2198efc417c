#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "pipeline/io/files.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/image_sequence_source.hpp"
#include "pipeline/io/libav_video_source.hpp"

namespace neopipe::pipeline::io {
namespace fs = std::filesystem;

bool has_image_extension(const std::string& path) {
  static constexpr std::array<const char*, 16> kExt{".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm",
                                                    ".pbm", ".pnm", ".webp", ".jp2", ".exr", ".hdr",  ".sr",  ".ras"};
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::find(kExt.begin(), kExt.end(), ext) != kExt.end();
}

std::unique_ptr<FrameSource> open_frame_source(const std::vector<std::string>& inputs, ColorFormat format) {
  if (inputs.empty()) throw SourceError("no input given");
  std::vector<std::string> images;
  std::vector<std::string> videos;
  for (const auto& in : inputs) {
    std::error_code ec;
    const auto status = fs::status(in, ec);
    if (ec || !fs::exists(status)) throw SourceError(in + ": no such file or directory");
    if (fs::is_directory(status)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(in, ec)) {
        if (e.is_regular_file() && has_image_extension(e.path().string())) found.push_back(e.path().string());
      }
      if (ec) throw SourceError(in + ": cannot list the directory: " + ec.message());
      if (found.empty()) throw SourceError(in + ": the directory holds no image files");
      std::sort(found.begin(), found.end());
      images.insert(images.end(), found.begin(), found.end());
      continue;
    }
    require_readable(in);
    // haveImageReader looks at the file's signature, not its name.
    if (cv::haveImageReader(in)) {
      images.push_back(in);
    } else if (has_image_extension(in)) {
      throw SourceError(in + ": not an image OpenCV can read (unknown format or corrupt file)");
    } else {
      videos.push_back(in);
    }
  }
  if (!videos.empty()) {
    if (inputs.size() > 1) {
      throw SourceError(videos.front() + ": give one video, or any number of images (" + std::to_string(inputs.size()) +
                        " inputs were given)");
    }
    return std::make_unique<LibavVideoSource>(videos.front(), format);
  }
  std::string description = images.size() == 1 ? images.front()
                                               : std::to_string(images.size()) + " images from " +
                                                     (inputs.size() == 1 ? inputs.front() : inputs.front() + ", ...");
  return std::make_unique<ImageSequenceSource>(std::move(images), format, std::move(description));
}

}  // namespace neopipe::pipeline::io
