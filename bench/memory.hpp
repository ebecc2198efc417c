#pragma once
// Resident memory of this process, for `neopipe bench`: the peak over the whole run, and how much
// one piece of work makes the resident set grow above where it stood before (Linux /proc; elsewhere
// getrusage where it can, else nothing).

#include <cstdint>
#include <optional>

namespace neopipe::bench {

/// The process's peak resident set size so far, in bytes (VmHWM, or getrusage's ru_maxrss). Peaks
/// that PeakGrowth reset are not lost: the highest ever seen is remembered.
std::optional<std::int64_t> peak_rss_bytes();

/// Measures how far the resident set rises above its starting point while an object lives: the
/// constructor hands free heap memory back to the system (malloc_trim), resets the kernel's peak
/// (/proc/self/clear_refs) and notes the current size; growth() is the peak since, minus that.
/// Without a resettable peak (not Linux, or /proc not writable) growth() is nullopt.
class PeakGrowth {
 public:
  PeakGrowth();
  std::optional<std::int64_t> growth() const;  ///< bytes, >= 0

 private:
  std::optional<std::int64_t> start_;
};

}  // namespace neopipe::bench
