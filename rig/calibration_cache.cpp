#include "rig/calibration_cache.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <opencv2/core/persistence.hpp>
#include <system_error>

namespace neopipe::rig {
namespace {

constexpr const char* kKeyNode = "neopipe_cache_key";

// FNV-1a: the same file name for the same key on every machine and build.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

// OpenCV's messages span lines; a note is one.
std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

CalibrationCache::CalibrationCache(std::filesystem::path dir, std::function<void(const std::string&)> note)
    : dir_(std::move(dir)), note_(std::move(note)) {}

std::optional<std::filesystem::path> CalibrationCache::default_dir() {
  const auto env = [](const char* name) -> std::optional<std::string> {
    const char* v = std::getenv(name);  // NOLINT(concurrency-mt-unsafe): read before any thread starts
    if (v == nullptr || *v == '\0') return std::nullopt;
    return std::string(v);
  };
  if (auto d = env("NEOPIPE_CACHE_DIR")) return std::filesystem::path(*d);
  if (auto d = env("XDG_CACHE_HOME")) return std::filesystem::path(*d) / "neopipe";
  if (auto d = env("HOME")) return std::filesystem::path(*d) / ".cache" / "neopipe";
  return std::nullopt;
}

std::filesystem::path CalibrationCache::file_for(const std::string& key) const {
  return dir_ / fmt::format("global-camera-{:016x}.yml", fnv1a(key));
}

std::optional<calib::Calibration> CalibrationCache::load(const std::filesystem::path& file,
                                                         const std::string& key) const {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  try {
    std::string stored;
    {
      const cv::FileStorage fs(file.string(), cv::FileStorage::READ);
      if (!fs.isOpened()) throw calib::CalibrationError(file.string() + ": cannot be read");
      const cv::FileNode node = fs[kKeyNode];
      if (!node.isString()) throw calib::CalibrationError(file.string() + ": no cache key");
      node >> stored;
    }
    if (stored != key) return std::nullopt;  // stale, or another key with the same hash: recalibrate
    calib::Calibration c = calib::load_calibration(file.string());
    if (c.model != calib::Model::full) throw calib::CalibrationError(file.string() + ": not a full camera model");
    return c;
  } catch (const std::exception& e) {  // OpenCV's parser throws cv::Exception for a mangled file
    if (note_)
      note_(fmt::format("{}: corrupt cached calibration, recalibrating ({})", file.string(), one_line(e.what())));
    return std::nullopt;
  }
}

void CalibrationCache::store(const std::filesystem::path& file, const std::string& key,
                             const calib::Calibration& c) const {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  // Written aside and renamed into place, so a reader never sees half a file and two runs racing
  // each leave a whole one.
  const std::filesystem::path temp = file.string() + fmt::format(".{}.tmp", ::getpid());
  try {
    calib::save_calibration(c, temp.string());
    {
      cv::FileStorage fs(temp.string(), cv::FileStorage::APPEND);
      if (!fs.isOpened()) throw calib::CalibrationError(temp.string() + ": cannot be appended to");
      fs << kKeyNode << key;
    }
    std::filesystem::rename(temp, file);
  } catch (const std::exception&) {
    std::filesystem::remove(temp, ec);
  }
}

calib::Calibration CalibrationCache::get(const std::string& key,
                                         const std::function<calib::Calibration()>& calibrate) const {
  const std::filesystem::path file = file_for(key);
  if (auto cached = load(file, key)) return *std::move(cached);
  calib::Calibration c = calibrate();
  store(file, key, c);
  return c;
}

}  // namespace neopipe::rig
