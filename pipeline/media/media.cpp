#include "pipeline/media/media.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

#include "pipeline/media/media_backend.hpp"

namespace neopipe::pipeline::media {
namespace {
namespace fs = std::filesystem;

constexpr const char* kPluginFile = "libneopipe_media.so";

std::vector<std::string> plugin_candidates() {
  std::vector<std::string> paths;
  const auto add = [&paths](const fs::path& path) {
    const std::string p = path.lexically_normal().string();
    if (std::find(paths.begin(), paths.end(), p) == paths.end()) paths.push_back(p);
  };
  // A path the user names wins: programs that link the installed libraries live anywhere.
  if (const char* named = std::getenv("NEOPIPE_MEDIA_PLUGIN"); named != nullptr && *named != '\0') add(named);
  // Beside the running program, so a copied build directory uses its own plug-in; then where
  // `cmake --install` puts it relative to the program (bin/ -> lib/neopipe/), so an installed tree
  // works wherever its prefix is; then where the build put it, for programs in other directories
  // (the tests).
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    add(exe.parent_path() / kPluginFile);
    add(exe.parent_path() / NEOPIPE_MEDIA_PLUGIN_RELATIVE_DIR / kPluginFile);
  }
  // Beside the shared object this code was linked into, when that is not the program: the Python
  // module (python/) carries its plug-in in its package directory, wherever that is installed.
  Dl_info self{};
  if (dladdr(reinterpret_cast<const void*>(&plugin_candidates), &self) != 0 && self.dli_fname != nullptr)
    add(fs::path(self.dli_fname).parent_path() / kPluginFile);
  add(NEOPIPE_MEDIA_PLUGIN_PATH);
  return paths;
}

const MediaBackend* load_plugin() {
  std::string tried;
  for (const auto& path : plugin_candidates()) {
    if (!tried.empty()) tried += "; ";
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      tried += path + ": no such file";
      continue;
    }
    // Never closed: writers and readers the plug-in made may live until the process ends, and
    // unloading OpenCV's codecs at exit gains nothing.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      tried += why != nullptr ? std::string(why) : path + ": cannot be loaded";
      continue;
    }
    using Entry = decltype(&neopipe_media_backend);
    auto* entry = reinterpret_cast<Entry>(dlsym(handle, kMediaBackendEntry));  // NOLINT: dlsym's contract
    int version = 0;
    const MediaBackend* backend = entry != nullptr ? entry(&version) : nullptr;
    if (backend == nullptr || version != kMediaBackendVersion) {
      tried += path + ": not this build's media plug-in (rebuild it)";
      dlclose(handle);
      continue;
    }
    return backend;
  }
  throw MediaError("the media plug-in cannot be loaded (" + tried + ")");
}

const MediaBackend& backend(const std::string& path) {
  try {
    // A function-local static: loaded once, by whichever thread comes first; a failed load is
    // retried by the next call.
    static const MediaBackend* const loaded = load_plugin();
    return *loaded;
  } catch (const MediaError& e) {
    throw MediaError(path + ": " + e.what());
  }
}

}  // namespace

cv::Mat read_image(const std::string& path, ImageMode mode) {
  return backend(path).read_image(path, mode);
}

bool write_image(const std::string& path, const cv::Mat& image) {
  return backend(path).write_image(path, image);
}

bool have_image_reader(const std::string& path) {
  return backend(path).have_image_reader(path);
}

std::unique_ptr<VideoWriter> open_video_writer(const std::string& path, double fps, cv::Size size) {
  return backend(path).open_video_writer(path, fourcc_for(path), fps, size);
}

std::unique_ptr<VideoReader> open_video_reader(const std::string& path) {
  return backend(path).open_video_reader(path);
}

int fourcc_for(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".avi" ? fourcc('M', 'J', 'P', 'G') : fourcc('m', 'p', '4', 'v');
}

bool plugin_loaded() {
  // Asked of the dynamic loader rather than remembered, so this file keeps no state of its own.
  for (const auto& path : plugin_candidates()) {
    if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD); handle != nullptr) {
      dlclose(handle);  // drops only the reference RTLD_NOLOAD took
      return true;
    }
  }
  return false;
}

}  // namespace neopipe::pipeline::media
