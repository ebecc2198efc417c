#pragma once
// A cache of the global camera's calibration sessions (rig/global_camera.hpp). A session costs
// seconds on every `neopipe nav` run, yet depends only on the camera, its realism, the workspace,
// the board and the seed: it is stored under a key that spells all of them out (session_key), and
// used again only when the key matches exactly. A stale entry (another key, an older recipe) is recalibrated and
// replaced without a word; a corrupt one is recalibrated and replaced with a one-line note. Never is
// a calibration used for a rig it was not made for.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "rig/global_camera.hpp"

namespace neopipe::rig {

class CalibrationCache {
 public:
  /// A cache in `dir` (created when first written). `note`, if set, hears one line per corrupt entry.
  explicit CalibrationCache(std::filesystem::path dir, std::function<void(const std::string&)> note = {});

  /// The default folder: $NEOPIPE_CACHE_DIR, else $XDG_CACHE_HOME/neopipe, else ~/.cache/neopipe;
  /// none when neither is set (then nothing is cached).
  static std::optional<std::filesystem::path> default_dir();

  /// The session stored under `key`, or `calibrate()`'s, which is then stored. A store that fails
  /// (read-only folder, full disk) only costs the next run its time: it is not an error.
  GlobalCameraSession get(const std::string& key, const std::function<GlobalCameraSession()>& calibrate) const;

  /// The file an entry for `key` lives in.
  [[nodiscard]] std::filesystem::path file_for(const std::string& key) const;

 private:
  std::optional<GlobalCameraSession> load(const std::filesystem::path& file, const std::string& key) const;
  void store(const std::filesystem::path& file, const std::string& key, const GlobalCameraSession& s) const;

  std::filesystem::path dir_;
  std::function<void(const std::string&)> note_;
};

}  // namespace neopipe::rig
