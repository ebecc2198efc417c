#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "pipeline/io/files.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/image_sequence_source.hpp"
#include "pipeline/io/image_signature.hpp"
#include "pipeline/io/libav_video_source.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::pipeline::io {
namespace fs = std::filesystem;

bool has_image_extension(const std::string& path) {
  static constexpr std::array<const char*, 16> kExt{".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm",
                                                    ".pbm", ".pnm", ".webp", ".jp2", ".exr", ".hdr",  ".sr",  ".ras"};
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::find(kExt.begin(), kExt.end(), ext) != kExt.end();
}

namespace {

bool have_image_reader_or_false(const std::string& path) {
  try {
    return media::have_image_reader(path);
  } catch (const media::MediaError&) {
    return false;  // the caller's own error says more about the file than a missing plug-in
  }
}

}  // namespace

bool is_image_file(const std::string& path) {
  // The signature first, as cv::haveImageReader decides, without loading OpenCV's codecs; a file
  // named as an image without a signature known here is left to the codecs themselves.
  if (file_has_image_signature(path)) return true;
  return has_image_extension(path) && have_image_reader_or_false(path);
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
    if (is_image_file(in)) {
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
    try {
      return std::make_unique<LibavVideoSource>(videos.front(), format);
    } catch (const SourceError&) {
      // An image format without a signature test here (see image_signature.hpp) that OpenCV still
      // reads: ask the codecs themselves, now that the file is known not to be a video.
      if (!have_image_reader_or_false(videos.front())) throw;
      images = videos;
    }
  }
  std::string description = images.size() == 1 ? images.front()
                                               : std::to_string(images.size()) + " images from " +
                                                     (inputs.size() == 1 ? inputs.front() : inputs.front() + ", ...");
  return std::make_unique<ImageSequenceSource>(std::move(images), format, std::move(description));
}

}  // namespace neopipe::pipeline::io
