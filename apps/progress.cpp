#include "apps/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace neopipe::apps {

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) != 0;
}

ProgressBar::ProgressBar(std::string label, std::optional<std::int64_t> total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && stderr_is_terminal()) {}

ProgressBar::~ProgressBar() {
  clear();
}

void ProgressBar::update(std::int64_t done, const std::string& detail) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  std::string line;
  if (total_ && *total_ > 0) {
    constexpr int kWidth = 30;
    const double f = std::clamp(static_cast<double>(done) / static_cast<double>(*total_), 0.0, 1.0);
    const int filled = static_cast<int>(f * kWidth);
    line = fmt::format("\r{} [{}{}] {}/{} {}", label_, std::string(static_cast<size_t>(filled), '#'),
                       std::string(static_cast<size_t>(kWidth - filled), '.'), done, *total_, detail);
  } else {
    line = fmt::format("\r{} {} {}", label_, done, detail);
  }
  std::fputs(line.c_str(), stderr);
  std::fputs("\x1b[K", stderr);  // erase the rest of the line
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::clear() {
  if (!drawn_) return;
  std::fputs("\r\x1b[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace neopipe::apps
