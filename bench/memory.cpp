#include "bench/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace neopipe::bench {
namespace {

// The highest VmHWM seen before a PeakGrowth reset it.
std::int64_t g_forgotten_peak = 0;

// A "Name:   1234 kB" line of /proc/self/status, in bytes.
std::optional<std::int64_t> status_field(const std::string& name) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, name.size() + 1, name + ":") != 0) continue;
    std::istringstream fields(line.substr(name.size() + 1));
    std::int64_t kib = 0;
    if (fields >> kib) return kib * 1024;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::int64_t> peak_rss_bytes() {
  auto peak = status_field("VmHWM");
  if (!peak) {
    rusage u{};
    if (getrusage(RUSAGE_SELF, &u) != 0) return std::nullopt;
    peak = static_cast<std::int64_t>(u.ru_maxrss) * 1024;  // KiB on Linux
  }
  return std::max(*peak, g_forgotten_peak);
}

PeakGrowth::PeakGrowth() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  const auto before = status_field("VmHWM");
  if (!before) return;
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // since Linux 4.0: reset the peak resident set size to the current one
  clear.flush();
  if (!clear) return;
  g_forgotten_peak = std::max(g_forgotten_peak, *before);
  const auto rss = status_field("VmRSS");
  const auto peak = status_field("VmHWM");
  // A kernel that ignores the request leaves the old peak: then there is nothing to measure.
  if (rss && peak && *peak <= *rss + (1 << 20)) start_ = rss;
}

std::optional<std::int64_t> PeakGrowth::growth() const {
  if (!start_) return std::nullopt;
  const auto peak = status_field("VmHWM");
  if (!peak) return std::nullopt;
  return std::max<std::int64_t>(0, *peak - *start_);
}

}  // namespace neopipe::bench
