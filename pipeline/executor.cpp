#include "pipeline/executor.hpp"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "pipeline/frame_size.hpp"
#include "pipeline/fusion.hpp"

namespace neopipe::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

// Names the node and frame an error came from, keeping the original message.
class NodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace

class Executor::Impl {
 public:
  Impl(CompiledGraph graph, ExecutorOptions o, ResultHandler handler)
      : graph_(std::move(graph)),
        threads_(o.threads > 0 ? o.threads : tbb::info::default_concurrency()),
        frames_in_flight_(o.frames_in_flight > 0 ? std::max(o.frames_in_flight, 2) : 2 * (threads_ + 2)),
        min_stripe_rows_(std::max(o.min_stripe_rows, 1)),
        fused_stripe_rows_(std::max(o.fused_stripe_rows, 0)),
        refill_slack_(std::max(0, frames_in_flight_ / 2 - 1)),
        on_result_(std::move(handler)),
        // The driver thread does not join the arena, so the pool needs `threads_` workers of its own.
        control_(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads_) + 1),
        arena_(threads_, 0) {
    const size_t n = graph_.nodes().size();
    // A task runs a step: one node, or a fused group named by its sink. Absorbed members have no
    // task; their inputs from outside the group become the sink's.
    absorbed_.assign(n, false);
    fused_.resize(n);
    step_inputs_.resize(n);
    in_order_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      in_order_[i] = graph_.nodes()[i].impl->frame_order() == FrameOrder::in_order;
      for (size_t k = 0; k < graph_.nodes()[i].inputs.size(); ++k) step_inputs_[i].push_back({static_cast<int>(i), k});
    }
    if (o.fuse) {
      for (auto& members : plan_fusion(graph_)) {
        auto step = std::make_unique<FusedStep>(graph_, std::move(members));
        const auto sink = static_cast<size_t>(step->sink());
        step_inputs_[sink].clear();
        for (const int m : step->members()) {
          const auto mi = static_cast<size_t>(m);
          for (size_t k = 0; k < graph_.nodes()[mi].inputs.size(); ++k) {
            if (!step->internal(m, k)) step_inputs_[sink].push_back({m, k});
          }
          if (m != step->sink()) {
            absorbed_[mi] = true;
            step_inputs_[mi].clear();
            in_order_[sink] = in_order_[sink] || in_order_[mi];
          }
        }
        fused_[sink] = std::move(step);
      }
    }
    consumers_now_.resize(n);
    consumers_next_.resize(n);
    consumers_first_.resize(n);
    for (size_t c = 0; c < n; ++c) {
      for (const auto& [member, k] : step_inputs_[c]) {
        const auto& in = graph_.nodes()[static_cast<size_t>(member)].inputs[k];
        if (!in.from.valid()) continue;
        const auto p = static_cast<size_t>(in.from.node);
        (in.delayed ? consumers_next_ : consumers_now_)[p].push_back(static_cast<int>(c));
        if (in.delayed && in.initial_from.valid()) {
          consumers_first_[static_cast<size_t>(in.initial_from.node)].push_back(static_cast<int>(c));
        }
      }
    }
    slots_.resize(static_cast<size_t>(frames_in_flight_));
    for (auto& s : slots_) {
      s.values.resize(n);
      for (size_t i = 0; i < n; ++i) s.values[i].resize(graph_.nodes()[i].impl->outputs().size());
    }
  }

  ~Impl() {
    std::unique_lock lk(m_);
    cv_.wait(lk, [&] { return running_ == 0; });
  }

  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  bool submit(std::int64_t index, const cv::Mat& frame, bool block) {
    check_frame(frame);
    std::unique_lock lk(m_);
    for (;;) {
      deliver(lk);
      if (error_) fail(lk);
      if (can_admit(next_seq_)) {
        admit(lk, index, frame);
        deliver(lk);
        return true;
      }
      if (!block) return false;
      // Waits until several slots are free rather than one, so that the driver wakes once per few
      // frames instead of once per frame: each wake-up takes a core from a worker on a small machine.
      cv_.wait(lk, [&] { return error_ || running_ == 0 || can_admit(next_seq_ + refill_slack_); });
    }
  }

  void poll() {
    std::unique_lock lk(m_);
    deliver(lk);
    if (error_) fail(lk);
  }

  void finish() {
    std::unique_lock lk(m_);
    for (;;) {
      deliver(lk);
      if (error_) fail(lk);
      if (delivered_ == next_seq_) return;
      cv_.wait(lk);
    }
  }

  const CompiledGraph& graph() const { return graph_; }
  int threads() const { return threads_; }
  int frames_in_flight() const { return frames_in_flight_; }

 private:
  struct Slot {
    std::int64_t seq = -1;
    std::int64_t index = 0;
    cv::Mat input;
    std::vector<std::vector<Value>> values;  // [node][output port]
    std::vector<int> pending;                // unmet dependencies per node
    std::vector<char> done;
    int remaining = 0;  // nodes not yet done
    Clock::time_point submitted;
  };
  struct Task {
    std::int64_t seq;
    int node;
  };

  Slot& slot(std::int64_t seq) { return slots_[static_cast<size_t>(seq % frames_in_flight_)]; }

  // Called on the driver thread only, before admission, so no task can be running on a first frame.
  void check_frame(const cv::Mat& frame) {
    const int want = cv_type(graph_.source_type());
    const std::int64_t seq = next_seq_;
    if (frame.empty() || frame.type() != want) {
      throw std::invalid_argument("frame " + std::to_string(seq) + ": the graph's source takes " +
                                  std::string(to_string(graph_.source_type())) + " (" + cv::typeToString(want) +
                                  ") images, got " + (frame.empty() ? "an empty one" : cv::typeToString(frame.type())));
    }
    if (!configured_) {
      configure(frame.size());
    } else if (frame.size() != size_) {
      throw std::invalid_argument("frame " + std::to_string(seq) + " is " + size_text(frame.size()) +
                                  " but the stream started at " + size_text(size_));
    }
  }

  void configure(cv::Size size) {
    for (auto& n : graph_.nodes()) {
      try {
        n.impl->configure(size);
      } catch (const std::invalid_argument& e) {
        throw GraphError(n.where, "node '" + n.name + "': " + e.what());
      }
    }
    for (auto& step : fused_) {
      if (step) step->configure(size, fused_stripe_rows_);
    }
    initial_values_.resize(graph_.nodes().size());
    for (size_t i = 0; i < graph_.nodes().size(); ++i) {
      const auto& node = graph_.nodes()[i];
      initial_values_[i].resize(node.inputs.size());
      for (size_t k = 0; k < node.inputs.size(); ++k) {
        const auto& in = node.inputs[k];
        if (in.delayed && !in.initial_from.valid()) {
          initial_values_[i][k] = constant_value(graph_.type_of(in.from), size, in.initial_fill);
        }
      }
    }
    size_ = size;
    configured_ = true;
  }

  // Frame `seq` takes the slot of frame seq - K, which must be complete, and so must frame
  // seq - K + 1 if delayed edges read the previous frame's slot.
  bool can_admit(std::int64_t seq) const {
    const std::int64_t need = seq - frames_in_flight_ + 1 + (graph_.has_delays() ? 1 : 0);
    return complete_prefix_ >= need;
  }

  void admit(std::unique_lock<std::mutex>& lk, std::int64_t index, const cv::Mat& frame) {
    const std::int64_t seq = next_seq_++;
    Slot& s = slot(seq);
    const size_t n = graph_.nodes().size();
    // Image outputs were handed to earlier results: let go of them so nodes allocate fresh ones.
    for (const auto& o : graph_.outputs()) s.values[static_cast<size_t>(o.node)][static_cast<size_t>(o.port)] = Value();
    s.seq = seq;
    s.index = index;
    s.input = frame;
    s.submitted = Clock::now();
    s.pending.assign(n, 0);
    s.done.assign(n, 0);
    const auto src = static_cast<size_t>(graph_.source());
    s.values[src][0] = frame;
    s.done[src] = 1;
    s.remaining = static_cast<int>(n) - 1;
    for (size_t i = 0; i < n; ++i) {
      if (absorbed_[i]) {
        s.done[i] = 1;  // runs inside its group's step
        --s.remaining;
      }
    }
    const Slot* prev = seq > 0 ? &slot(seq - 1) : nullptr;
    std::vector<Task> ready;
    for (size_t i = 0; i < n; ++i) {
      if (i == src || absorbed_[i]) continue;
      int pending = 0;
      for (const auto& [member, k] : step_inputs_[i]) {
        const auto& in = graph_.nodes()[static_cast<size_t>(member)].inputs[k];
        if (!in.from.valid()) continue;
        if (!in.delayed) {
          pending += s.done[static_cast<size_t>(in.from.node)] == 0 ? 1 : 0;
        } else if (prev == nullptr) {
          if (in.initial_from.valid()) pending += s.done[static_cast<size_t>(in.initial_from.node)] == 0 ? 1 : 0;
        } else {
          pending += prev->done[static_cast<size_t>(in.from.node)] == 0 ? 1 : 0;
        }
      }
      if (in_order_[i] && prev != nullptr && prev->done[i] == 0) ++pending;
      s.pending[i] = pending;
      if (pending == 0) ready.push_back({seq, static_cast<int>(i)});
    }
    if (s.remaining == 0) complete(seq);
    ready = claim(std::move(ready));
    lk.unlock();
    enqueue(ready);
    lk.lock();
  }

  // Counts `ready` as running. After an error only frames before the failed one go on, so that
  // every frame submitted before it is still delivered. Caller holds the lock.
  std::vector<Task> claim(std::vector<Task> ready) {
    if (error_) std::erase_if(ready, [&](const Task& t) { return t.seq >= error_seq_; });
    running_ += static_cast<int>(ready.size());
    return ready;
  }

  // Hands claimed tasks to the workers. Called without the lock.
  void enqueue(const std::vector<Task>& tasks) {
    for (const Task& t : tasks) arena_.enqueue([this, t] { run(t); });
  }

  void run(Task t) {
    Slot& s = slot(t.seq);
    const auto i = static_cast<size_t>(t.node);
    CompiledNode& node = graph_.nodes()[i];
    std::exception_ptr err;
    FusedStep* fused = fused_[i].get();
    try {
      // Inputs fed from inside a fused group are not whole images: they stay null here.
      std::vector<const Value*> inputs(node.inputs.size(), nullptr);
      for (size_t k = 0; k < node.inputs.size(); ++k) {
        if (fused == nullptr || !fused->internal(t.node, k)) inputs[k] = input_value(t.seq, i, k);
      }
      std::vector<Value*> outputs;
      for (auto& v : s.values[i]) outputs.push_back(&v);
      NodeIO io(inputs, outputs, node.impl->outputs(), size_);
      node.impl->begin_frame(io);
      if (fused != nullptr) {
        const auto external = [&](size_t pos, size_t k) -> const cv::Mat& {
          return std::get<cv::Mat>(*input_value(t.seq, static_cast<size_t>(fused->members()[pos]), k));
        };
        fused->run(graph_, external, io.out_image(0), threads_ > 1);
      } else if (node.impl->footprint() != kernels::Footprint::frame) {
        run_stripes(*node.impl, io);
      }
    } catch (const std::exception& e) {
      err = std::make_exception_ptr(NodeError("frame " + std::to_string(s.index) + ", node '" + node.name + "' (" +
                                              node.kernel + "): " + e.what()));
    } catch (...) {
      err =
          std::make_exception_ptr(NodeError("frame " + std::to_string(s.index) + ", node '" + node.name + "' failed"));
    }
    // This task stays counted in running_ until its very last touch of the executor, so the
    // executor (waiting for running_ == 0 in its destructor) cannot vanish while the task still
    // enqueues its successors.
    std::vector<Task> ready;
    bool wake = err != nullptr;
    {
      const std::lock_guard lk(m_);
      if (err) {
        record_error(err, t.seq);
      } else {
        const std::int64_t prefix = complete_prefix_;
        ready = claim(node_done(t));
        wake = complete_prefix_ != prefix;
      }
    }
    enqueue(ready);
    const std::lock_guard lk(m_);
    --running_;
    // The driver waits for frames to complete in order (a free slot, a result to deliver), for an
    // error, or for the last task to end; any other wake-up would only cost it a context switch.
    if (wake || running_ == 0) cv_.notify_all();
  }

  // What input k of node i reads on frame seq: its producer's value on this frame, or for a delayed
  // input the previous frame's (the initial value on the first frame). Null if unconnected.
  const Value* input_value(std::int64_t seq, size_t i, size_t k) {
    const auto& in = graph_.nodes()[i].inputs[k];
    if (!in.from.valid()) return nullptr;
    const auto at = [](Slot& s, PortAddress a) {
      return &s.values[static_cast<size_t>(a.node)][static_cast<size_t>(a.port)];
    };
    if (!in.delayed) return at(slot(seq), in.from);
    if (seq > 0) return at(slot(seq - 1), in.from);
    return in.initial_from.valid() ? at(slot(seq), in.initial_from) : &initial_values_[i][k];
  }

  void run_stripes(Node& node, NodeIO& io) const {
    const int h = size_.height;
    const int stripes = std::min(h / min_stripe_rows_, threads_ * 4);
    if (threads_ <= 1 || stripes < 2) {
      node.run_rows(io, {0, h});
      return;
    }
    // Round the stripe height up, then count the stripes again, so every stripe lies in the frame.
    const int rows = (h + stripes - 1) / stripes;
    const int count = (h + rows - 1) / rows;
    tbb::parallel_for(0, count, [&](int k) { node.run_rows(io, {k * rows, std::min(h, (k + 1) * rows)}); });
  }

  // Marks (seq, node) done and returns the tasks it made ready. Caller holds the lock.
  std::vector<Task> node_done(Task t) {
    std::vector<Task> ready;
    Slot& s = slot(t.seq);
    const auto i = static_cast<size_t>(t.node);
    s.done[i] = 1;
    --s.remaining;
    const auto release = [&](Slot& target, std::int64_t seq, int c) {
      if (--target.pending[static_cast<size_t>(c)] == 0) ready.push_back({seq, c});
    };
    for (const int c : consumers_now_[i]) release(s, t.seq, c);
    if (t.seq == 0) {
      for (const int c : consumers_first_[i]) release(s, t.seq, c);
    }
    if (next_seq_ > t.seq + 1) {
      Slot& next = slot(t.seq + 1);
      for (const int c : consumers_next_[i]) release(next, t.seq + 1, c);
      if (in_order_[i]) release(next, t.seq + 1, t.node);
    }
    if (s.remaining == 0) complete(t.seq);
    return ready;
  }

  void complete(std::int64_t seq) {
    Slot& s = slot(seq);
    FrameResult r;
    r.index = s.index;
    r.input = s.input;
    for (const auto& o : graph_.outputs())
      r.outputs.push_back(s.values[static_cast<size_t>(o.node)][static_cast<size_t>(o.port)]);
    r.latency_s = std::chrono::duration<double>(Clock::now() - s.submitted).count();
    finished_.emplace(seq, std::move(r));
    while (complete_prefix_ < next_seq_ && slot(complete_prefix_).seq == complete_prefix_ &&
           slot(complete_prefix_).remaining == 0) {
      ++complete_prefix_;
    }
  }

  // Keeps the error of the earliest frame: that is the one a sequential run would have hit first.
  void record_error(std::exception_ptr err, std::int64_t seq) {
    if (!error_ || seq < error_seq_) {
      error_ = std::move(err);
      error_seq_ = seq;
    }
  }

  // Hands finished results to the handler in order, without holding the lock during the call. A
  // handler that throws receives nothing more: its error stops the run like a node's.
  void deliver(std::unique_lock<std::mutex>& lk) {
    while (!handler_failed_) {
      const auto it = finished_.find(delivered_);
      if (it == finished_.end()) return;
      FrameResult r = std::move(it->second);
      finished_.erase(it);
      ++delivered_;
      lk.unlock();
      try {
        on_result_(std::move(r));
      } catch (...) {
        lk.lock();
        handler_failed_ = true;
        record_error(std::current_exception(), delivered_ - 1);
        throw;
      }
      lk.lock();
    }
  }

  [[noreturn]] void fail(std::unique_lock<std::mutex>& lk) {
    cv_.wait(lk, [&] { return running_ == 0; });
    deliver(lk);
    std::rethrow_exception(error_);
  }

  CompiledGraph graph_;
  int threads_;
  int frames_in_flight_;
  int min_stripe_rows_;
  int fused_stripe_rows_;
  int refill_slack_;  // extra free slots a blocked submit waits for (see submit)
  ResultHandler on_result_;
  tbb::global_control control_;
  tbb::task_arena arena_;

  std::vector<std::vector<int>> consumers_now_;     // per producer: consumer of each non-delayed edge
  std::vector<std::vector<int>> consumers_next_;    // per producer: consumer of each delayed edge
  std::vector<std::vector<int>> consumers_first_;   // per producer: consumer of each initial-value edge
  std::vector<std::vector<Value>> initial_values_;  // [node][input]: constant first-frame values
  std::vector<bool> in_order_;                      // per step: waits for its own previous frame
  std::vector<bool> absorbed_;                      // per node: runs inside a fused group's step
  std::vector<std::unique_ptr<FusedStep>> fused_;   // per node: the group it is the sink of, if any
  // Per step (indexed by its node, or its group's sink): the (member node, input) pairs fed from
  // outside the step.
  std::vector<std::vector<std::pair<int, size_t>>> step_inputs_;
  cv::Size size_;
  bool configured_ = false;

  std::mutex m_;
  std::condition_variable cv_;
  std::vector<Slot> slots_;
  std::int64_t next_seq_ = 0;
  std::int64_t complete_prefix_ = 0;
  std::int64_t delivered_ = 0;
  std::map<std::int64_t, FrameResult> finished_;
  int running_ = 0;
  std::exception_ptr error_;
  std::int64_t error_seq_ = 0;  // the frame error_ came from
  bool handler_failed_ = false;
};

Executor::Executor(CompiledGraph graph, ExecutorOptions options, ResultHandler on_result)
    : impl_(std::make_unique<Impl>(std::move(graph), options, std::move(on_result))) {}
Executor::~Executor() = default;
void Executor::submit(std::int64_t index, const cv::Mat& frame) {
  impl_->submit(index, frame, true);
}
bool Executor::try_submit(std::int64_t index, const cv::Mat& frame) {
  return impl_->submit(index, frame, false);
}
void Executor::poll() {
  impl_->poll();
}
void Executor::finish() {
  impl_->finish();
}
const CompiledGraph& Executor::graph() const {
  return impl_->graph();
}
int Executor::threads() const {
  return impl_->threads();
}
int Executor::frames_in_flight() const {
  return impl_->frames_in_flight();
}

std::vector<FrameResult> run_frames(CompiledGraph graph, const std::vector<cv::Mat>& frames, ExecutorOptions options) {
  std::vector<FrameResult> results;
  Executor ex(std::move(graph), options, [&](FrameResult&& r) { results.push_back(std::move(r)); });
  for (size_t i = 0; i < frames.size(); ++i) ex.submit(static_cast<std::int64_t>(i), frames[i]);
  ex.finish();
  return results;
}

}  // namespace neopipe::pipeline
