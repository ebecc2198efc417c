#pragma once
// The engine as Python sees it: Graph (one frame at a time, on the caller's thread) and Stream (the
// generator behind neopipe.run: the executor with frames in flight, fed from a Python iterable or
// from a video or images read on a thread of their own).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "calib/calibration.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/prefetching_source.hpp"

namespace neopipe::python {

namespace py = pybind11;

/// `threshold` as Python gives it (None, "otsu" or 0..255) and `connectivity` (4 or 8) as the built-in
/// blob graph's options; throws py::value_error with the allowed values.
pipeline::BlobGraphOptions builtin_options(const py::object& threshold, int connectivity);

class Graph {
 public:
  explicit Graph(pipeline::GraphSpec spec);

  /// The first blob output's table for `frame`, or py::value_error if the graph has none.
  py::array process(const py::array& frame);
  /// Every output by name: images as arrays (copies), histograms as 256 counts, blob tables.
  py::dict process_outputs(const py::array& frame);
  /// Forgets the frames seen: delays start from their initial values, frame numbers from 0, any size.
  void reset();

  const pipeline::GraphSpec& spec() const { return spec_; }
  std::string name() const { return spec_.name; }
  std::string origin() const { return spec_.origin; }
  std::vector<std::string> output_names() const;
  std::string source_type() const;
  std::int64_t frames() const;
  /// The data address of the frame the engine last read: the caller's array's, unless it had to be
  /// converted (a colour frame for a gray graph or the reverse). Lets tests prove no copy was made.
  std::uintptr_t last_frame_address() const { return last_frame_address_; }

 private:
  const std::vector<pipeline::Value>& run(const py::array& frame);

  pipeline::GraphSpec spec_;
  std::unique_ptr<pipeline::InlineRunner> runner_;
  std::optional<std::size_t> blob_output_;
  // Python threads may share a Graph and call process at once with the GIL released: one frame at a
  // time, as the runner's reused buffers need.
  std::mutex mutex_;
  std::uintptr_t last_frame_address_ = 0;
};

struct StreamConfig {
  std::optional<pipeline::GraphSpec> spec;  ///< none: the built-in blob graph
  pipeline::BlobGraphOptions builtin;
  int threads = 0;
  std::string calib;  ///< a calibration file: add X,Y as `neopipe run --calib` does
  double height = 0;  ///< with calib: the blobs' centres lie this far above the plane, mm
};

class Stream {
 public:
  /// Frames from a Python iterator of numpy arrays (read in place, not copied).
  Stream(StreamConfig config, py::iterator frames);
  /// Frames from files: one video, or images and directories of images, as `neopipe run` takes them.
  Stream(StreamConfig config, const std::vector<std::string>& inputs);
  ~Stream();
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

  /// The next frame's blob table; py::stop_iteration after the last.
  py::array next();
  /// "N images from DIR", the video's path, or "frames from Python".
  std::string description() const;

 private:
  struct Result {
    std::int64_t index;
    cv::Size size;
    pipeline::BlobList blobs;
  };
  void load_calibration();
  void start(pipeline::PortType first_frame_type);
  py::array table(const Result& r);
  bool feed_one();
  void release_delivered();

  StreamConfig config_;
  std::optional<calib::Calibration> calibration_;
  py::dtype world_dtype_;
  std::optional<py::iterator> frames_;
  std::unique_ptr<pipeline::io::FrameSource> file_source_;
  std::unique_ptr<pipeline::io::PrefetchingSource> prefetch_;
  // Arrays handed in and still read by the engine, oldest first: a frame's memory is read in place
  // until its result is out (and, when the graph has delays, until the next frame's is).
  std::deque<std::pair<std::int64_t, py::object>> in_flight_;
  std::deque<Result> results_;
  std::int64_t delivered_ = -1;  ///< index of the last result out of the executor
  bool keep_one_more_ = false;   ///< the graph has delays: keep the previous frame too
  std::size_t blob_output_ = 0;
  pipeline::PortType source_type_ = pipeline::PortType::gray8;
  std::int64_t next_index_ = 0;
  bool finished_ = false;
  std::exception_ptr error_;
  // Last, so it is destroyed first: its destructor waits for the frames in flight, whose memory the
  // arrays above own.
  std::unique_ptr<pipeline::Executor> executor_;
};

}  // namespace neopipe::python
