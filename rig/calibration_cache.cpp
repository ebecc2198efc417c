#include "rig/calibration_cache.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <opencv2/core/persistence.hpp>
#include <system_error>
#include <vector>

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

void write_stats(cv::FileStorage& fs, const std::string& prefix, const calib::ErrorStats& s) {
  fs << prefix + "_mean" << std::vector<double>{s.mean.x(), s.mean.y()};
  fs << prefix + "_sd" << std::vector<double>{s.sd.x(), s.sd.y()};
  fs << prefix + "_rms" << s.rms << prefix + "_max" << s.max << prefix + "_points" << s.points;
}

std::vector<double> read_pair(const cv::FileStorage& fs, const std::string& name) {
  std::vector<double> v;
  fs[name] >> v;
  if (v.size() != 2) throw calib::CalibrationError(name + ": expected two numbers");
  return v;
}

double read_number(const cv::FileStorage& fs, const std::string& name) {
  const cv::FileNode n = fs[name];
  if (!n.isReal() && !n.isInt()) throw calib::CalibrationError(name + ": missing");
  return static_cast<double>(n);
}

calib::ErrorStats read_stats(const cv::FileStorage& fs, const std::string& prefix) {
  calib::ErrorStats s;
  const auto mean = read_pair(fs, prefix + "_mean");
  const auto sd = read_pair(fs, prefix + "_sd");
  s.mean = {mean[0], mean[1]};
  s.sd = {sd[0], sd[1]};
  s.rms = read_number(fs, prefix + "_rms");
  s.max = read_number(fs, prefix + "_max");
  s.points = static_cast<int>(read_number(fs, prefix + "_points"));
  return s;
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

std::optional<GlobalCameraSession> CalibrationCache::load(const std::filesystem::path& file,
                                                          const std::string& key) const {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  try {
    GlobalCameraSession s;
    {
      const cv::FileStorage fs(file.string(), cv::FileStorage::READ);
      if (!fs.isOpened()) throw calib::CalibrationError(file.string() + ": cannot be read");
      const cv::FileNode node = fs[kKeyNode];
      if (!node.isString()) throw calib::CalibrationError(file.string() + ": no cache key");
      std::string stored;
      node >> stored;
      if (stored != key) return std::nullopt;  // stale, or another key with the same hash: recalibrate
      s.plane_height = read_number(fs, "plane_height_mm");
      s.marble_height = read_number(fs, "marble_height_mm");
      const int degree = static_cast<int>(read_number(fs, "bias_degree"));
      cv::Size size;
      fs["bias_image_size"] >> size;
      cv::Mat coefficients;
      fs["bias_coefficients_px"] >> coefficients;
      if (coefficients.type() != CV_64F || coefficients.cols != 2 ||
          coefficients.rows != calib::CentroidBias::terms(degree)) {
        throw calib::CalibrationError("bias_coefficients_px: malformed");
      }
      Eigen::MatrixX2d c(coefficients.rows, 2);
      for (int i = 0; i < coefficients.rows; ++i)
        c.row(i) << coefficients.at<double>(i, 0), coefficients.at<double>(i, 1);
      s.bias = calib::CentroidBias(degree, size, c);
      s.bias_held_out_px = read_stats(fs, "bias_held_out_px");
      s.plate_held_out_mm = read_stats(fs, "plate_held_out_mm");
      s.plate_marbles = static_cast<int>(read_number(fs, "plate_marbles"));
    }
    s.calibration = calib::load_calibration(file.string());
    if (s.calibration.model != calib::Model::full) {
      throw calib::CalibrationError(file.string() + ": not a full camera model");
    }
    return s;
  } catch (const std::exception& e) {  // OpenCV's parser throws cv::Exception for a mangled file
    if (note_)
      note_(fmt::format("{}: corrupt cached calibration, recalibrating ({})", file.string(), one_line(e.what())));
    return std::nullopt;
  }
}

void CalibrationCache::store(const std::filesystem::path& file, const std::string& key,
                             const GlobalCameraSession& s) const {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  // Written aside and renamed into place, so a reader never sees half a file and two runs racing
  // each leave a whole one.
  const std::filesystem::path temp = file.string() + fmt::format(".{}.tmp", ::getpid());
  try {
    calib::save_calibration(s.calibration, temp.string());
    {
      cv::FileStorage fs(temp.string(), cv::FileStorage::APPEND);
      if (!fs.isOpened()) throw calib::CalibrationError(temp.string() + ": cannot be appended to");
      fs << "plane_height_mm" << s.plane_height << "marble_height_mm" << s.marble_height;
      fs << "bias_degree" << s.bias.degree() << "bias_image_size" << s.bias.image_size();
      cv::Mat coefficients(static_cast<int>(s.bias.coefficients().rows()), 2, CV_64F);
      for (int i = 0; i < coefficients.rows; ++i) {
        coefficients.at<double>(i, 0) = s.bias.coefficients()(i, 0);
        coefficients.at<double>(i, 1) = s.bias.coefficients()(i, 1);
      }
      fs << "bias_coefficients_px" << coefficients;
      write_stats(fs, "bias_held_out_px", s.bias_held_out_px);
      write_stats(fs, "plate_held_out_mm", s.plate_held_out_mm);
      fs << "plate_marbles" << s.plate_marbles;
      fs << kKeyNode << key;
    }
    std::filesystem::rename(temp, file);
  } catch (const std::exception&) {
    std::filesystem::remove(temp, ec);
  }
}

GlobalCameraSession CalibrationCache::get(const std::string& key,
                                          const std::function<GlobalCameraSession()>& calibrate) const {
  const std::filesystem::path file = file_for(key);
  if (auto cached = load(file, key)) return *std::move(cached);
  GlobalCameraSession s = calibrate();
  store(file, key, s);
  return s;
}

}  // namespace neopipe::rig
