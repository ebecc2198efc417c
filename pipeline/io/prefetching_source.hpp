#pragma once
// Reads another frame source on a thread of its own, into a bounded queue, so that decoding a video
// overlaps with processing and delivering the frames before it.
//
// Two ways to fill the queue:
// - read ahead (pace = 0): as fast as the queue empties. The reader starts on a frame only when
//   there is room for it, so at most `capacity` frames are read and not yet taken, the one being
//   read included: memory stays bounded whatever the length of the stream.
// - paced (pace > 0, real time): frame i is read at start + i / pace (at once if reading is late),
//   and a frame that finds the queue full replaces the oldest queued one, which counts as dropped:
//   the newest frames win, and nothing waits longer than the queue is deep.
//
// Frames come out in stream order. The inner source's error is rethrown by next() after every frame
// read before it has been taken, so its place in the stream is kept. stop() and the destructor wake
// a reader that waits for room or for a frame's due time at once and join it; the `stop` flag is
// looked at before every read. A reader inside the inner source's next() finishes that call first.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stop_token>
#include <thread>

#include "pipeline/io/frame_source.hpp"

namespace neopipe::pipeline::io {

struct PrefetchOptions {
  int capacity = 2;                         ///< frames read and not yet taken, at most (>= 1)
  double pace = 0;                          ///< frames per second for paced (real-time) reading; 0 = read ahead
  const std::atomic<bool>* stop = nullptr;  ///< when set, no further frame is read
};

class PrefetchingSource final : public FrameSource {
 public:
  using Clock = std::chrono::steady_clock;

  /// Starts reading `inner` (which must outlive this object and is not to be used by anyone else
  /// until it is destroyed or stop() has returned). Paced reading times frame i from `start`.
  explicit PrefetchingSource(FrameSource& inner, PrefetchOptions options = {}, Clock::time_point start = Clock::now());
  ~PrefetchingSource() override;
  PrefetchingSource(const PrefetchingSource&) = delete;
  PrefetchingSource& operator=(const PrefetchingSource&) = delete;

  /// The next frame, waiting for it; nullopt after the last one, or once reading was stopped.
  /// Rethrows the inner source's error (once) after the frames read before it.
  std::optional<SourceFrame> next() override;
  /// Like next(), but waits at most `timeout`: returns false if no frame (nor the end, nor the
  /// error) came in that time, and true with `out` set as next() would set it otherwise.
  bool next_within(Clock::duration timeout, std::optional<SourceFrame>& out);

  /// Stops reading and waits for the reader thread to end; frames already queued can still be taken.
  void stop();

  std::string description() const override { return description_; }
  double fps() const override { return fps_; }
  std::optional<std::int64_t> frame_count() const override { return frame_count_; }

  /// True when reading ended because of the stop flag or stop(), not at the end of the stream.
  bool interrupted() const;
  /// Paced reading: frames replaced in a full queue so far.
  std::int64_t dropped() const;
  /// Paced reading: how far, at most, a read began after its frame's due time, in seconds.
  double max_lag_s() const;

 private:
  void read_loop(const std::stop_token& token);
  // Takes the next item if there is one; caller holds the lock.
  bool take(std::optional<SourceFrame>& out);

  FrameSource& inner_;
  PrefetchOptions options_;
  Clock::time_point start_;
  std::string description_;
  double fps_;
  std::optional<std::int64_t> frame_count_;

  mutable std::mutex m_;
  std::condition_variable_any cv_;  // a frame was queued or taken, or reading ended
  std::deque<SourceFrame> queue_;
  bool ended_ = false;  // the reader will queue nothing more
  bool interrupted_ = false;
  std::exception_ptr error_;  // the inner source's error, handed out after the queued frames
  std::int64_t dropped_ = 0;
  double max_lag_s_ = 0;

  std::jthread reader_;  // last: stopped and joined before the members it uses go away
};

}  // namespace neopipe::pipeline::io
