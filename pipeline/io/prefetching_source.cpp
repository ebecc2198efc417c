#include "pipeline/io/prefetching_source.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace neopipe::pipeline::io {

PrefetchingSource::PrefetchingSource(FrameSource& inner, PrefetchOptions options, Clock::time_point start)
    : inner_(inner),
      options_(options),
      start_(start),
      description_(inner.description()),
      fps_(inner.fps()),
      frame_count_(inner.frame_count()) {
  if (options_.capacity < 1) {
    throw std::invalid_argument("read-ahead queue capacity must be at least 1, not " +
                                std::to_string(options_.capacity));
  }
  reader_ = std::jthread([this](const std::stop_token& token) { read_loop(token); });
}

PrefetchingSource::~PrefetchingSource() {
  stop();
}

void PrefetchingSource::stop() {
  if (!reader_.joinable()) return;
  reader_.request_stop();
  reader_.join();
}

void PrefetchingSource::read_loop(const std::stop_token& token) {
  const bool paced = options_.pace > 0;
  const auto period =
      paced ? std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options_.pace))
            : Clock::duration::zero();
  const auto capacity = static_cast<size_t>(options_.capacity);
  const auto end_reading = [&](bool interrupted, std::exception_ptr error) {
    const std::lock_guard lk(m_);
    ended_ = true;
    interrupted_ = interrupted;
    error_ = std::move(error);
    cv_.notify_all();
  };
  try {
    for (std::int64_t i = 0;; ++i) {
      const auto due = start_ + i * period;
      {
        std::unique_lock lk(m_);
        if (paced) {
          // Wakes early only when stopped: the predicate never holds.
          cv_.wait_until(lk, token, due, [] { return false; });
        } else {
          // Room first, then read: the frame being read counts against the capacity too.
          cv_.wait(lk, token, [&] { return queue_.size() < capacity; });
        }
      }
      if (token.stop_requested() || (options_.stop != nullptr && options_.stop->load())) {
        end_reading(true, nullptr);
        return;
      }
      std::optional<SourceFrame> f = inner_.next();
      if (!f) {
        end_reading(false, nullptr);
        return;
      }
      const std::lock_guard lk(m_);
      if (paced) {
        max_lag_s_ = std::max(max_lag_s_, std::chrono::duration<double>(Clock::now() - due).count());
        if (queue_.size() >= capacity) {
          queue_.pop_front();  // the newest frames win
          ++dropped_;
        }
      }
      queue_.push_back(std::move(*f));
      cv_.notify_all();
    }
  } catch (...) {
    end_reading(false, std::current_exception());
  }
}

bool PrefetchingSource::take(std::optional<SourceFrame>& out) {
  if (!queue_.empty()) {
    out = std::move(queue_.front());
    queue_.pop_front();
    cv_.notify_all();  // room for the reader
    return true;
  }
  if (!ended_) return false;
  out.reset();
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  return true;
}

std::optional<SourceFrame> PrefetchingSource::next() {
  std::unique_lock lk(m_);
  cv_.wait(lk, [&] { return !queue_.empty() || ended_; });
  std::optional<SourceFrame> out;
  take(out);
  return out;
}

bool PrefetchingSource::next_within(Clock::duration timeout, std::optional<SourceFrame>& out) {
  std::unique_lock lk(m_);
  if (!cv_.wait_for(lk, timeout, [&] { return !queue_.empty() || ended_; })) return false;
  return take(out);
}

bool PrefetchingSource::interrupted() const {
  const std::lock_guard lk(m_);
  return interrupted_;
}

std::int64_t PrefetchingSource::dropped() const {
  const std::lock_guard lk(m_);
  return dropped_;
}

double PrefetchingSource::max_lag_s() const {
  const std::lock_guard lk(m_);
  return max_lag_s_;
}

}  // namespace neopipe::pipeline::io
