#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace neopipe::apps {

class ProgressBar {
 public:
  /// `total` may be unknown; `enabled` false draws nothing (e.g. --quiet).
  ProgressBar(std::string label, std::optional<std::int64_t> total, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Redraws at most ten times a second.
  void update(std::int64_t done, const std::string& detail = "");
  /// Erases the bar.
  void clear();

 private:
  std::string label_;
  std::optional<std::int64_t> total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

/// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace neopipe::apps
