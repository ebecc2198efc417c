#include "python/src/engine.hpp"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "calib/plane_pose.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/source_location.hpp"
#include "python/src/frames.hpp"

namespace neopipe::python {
namespace {

namespace pl = neopipe::pipeline;
namespace io = neopipe::pipeline::io;

pl::PortType frame_type(const cv::Mat& m) {
  return m.channels() == 3 ? pl::PortType::bgr8 : pl::PortType::gray8;
}

// The frame the graph's source takes: `view` itself when its format matches, else converted as the
// file readers convert (BT.601 gray, as cv::cvtColor), which is a copy.
cv::Mat as_source(const cv::Mat& view, pl::PortType want) {
  if (frame_type(view) == want) return view;
  cv::Mat out;
  cv::cvtColor(view, out, want == pl::PortType::gray8 ? cv::COLOR_BGR2GRAY : cv::COLOR_GRAY2BGR);
  return out;
}

pl::CompiledGraph compile_blob_graph(const pl::GraphSpec& spec, std::size_t& blob_output) {
  pl::CompiledGraph graph = pl::compile(spec, pl::standard_kernels());
  const auto found = graph.find_output(pl::PortType::blobs);
  // The CLI's words (apps/run_command.cpp), so a script and a shell session read the same error.
  if (!found) {
    throw pl::GraphError({graph.origin(), 0, 0},
                         "the graph has no output of type blobs, so there is no blob table to write");
  }
  blob_output = *found;
  return graph;
}

}  // namespace

pl::BlobGraphOptions builtin_options(const py::object& threshold, int connectivity) {
  pl::BlobGraphOptions o;
  if (connectivity != 4 && connectivity != 8) {
    throw py::value_error(fmt::format("connectivity {}: must be 4 or 8", connectivity));
  }
  o.connectivity = connectivity;
  if (threshold.is_none()) return o;
  if (py::isinstance<py::str>(threshold)) {
    if (threshold.cast<std::string>() != "otsu") {
      throw py::value_error(fmt::format("threshold '{}': must be 0..255 or 'otsu'", threshold.cast<std::string>()));
    }
    return o;
  }
  if (!py::isinstance<py::int_>(threshold) || py::isinstance<py::bool_>(threshold)) {
    throw py::value_error(
        fmt::format("threshold {}: must be an int 0..255, 'otsu' or None", std::string(py::repr(threshold))));
  }
  const long t = threshold.cast<long>();
  if (t < 0 || t > 255) throw py::value_error(fmt::format("threshold {}: must be 0..255 or 'otsu'", t));
  o.threshold = static_cast<int>(t);
  return o;
}

// ---------------------------------------------------------------------------------------------------------------
// Graph

Graph::Graph(pl::GraphSpec spec) : spec_(std::move(spec)) {
  reset();
}

void Graph::reset() {
  std::lock_guard lock(mutex_);
  pl::CompiledGraph graph = pl::compile(spec_, pl::standard_kernels());
  blob_output_ = graph.find_output(pl::PortType::blobs);
  runner_ = std::make_unique<pl::InlineRunner>(std::move(graph));
}

std::vector<std::string> Graph::output_names() const {
  return runner_->graph().output_names();
}
std::string Graph::source_type() const {
  return std::string(pl::to_string(runner_->graph().source_type()));
}
std::int64_t Graph::frames() const {
  return runner_->frames();
}

const std::vector<pl::Value>& Graph::run(const py::array& frame) {
  const cv::Mat view = frame_view(frame);
  const std::vector<pl::Value>* outputs = nullptr;
  {
    // The engine touches no Python object: other Python threads run meanwhile.
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    const cv::Mat input = as_source(view, runner_->graph().source_type());
    last_frame_address_ = reinterpret_cast<std::uintptr_t>(input.data);
    try {
      outputs = &runner_->run(input);
    } catch (const std::invalid_argument& e) {
      // The runner's own words ("frame 3 is 320x240 but the first was 640x480") are about the caller's array.
      throw py::value_error(e.what());
    }
  }
  return *outputs;
}

py::array Graph::process(const py::array& frame) {
  if (!blob_output_) {
    throw py::value_error(
        fmt::format("{}: the graph has no output of type blobs (process_outputs gives its outputs)", spec_.origin));
  }
  const auto& outputs = run(frame);
  return blob_table(runner_->frames() - 1, std::get<pl::BlobList>(outputs[*blob_output_]));
}

py::dict Graph::process_outputs(const py::array& frame) {
  const auto& outputs = run(frame);
  const auto& names = runner_->graph().output_names();
  py::dict out;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const pl::Value& v = outputs[i];
    py::object value = py::none();
    if (const auto* m = std::get_if<cv::Mat>(&v)) {
      value = image_array(*m);
    } else if (const auto* h = std::get_if<pl::Histogram>(&v)) {
      py::array_t<std::int64_t> counts(static_cast<py::ssize_t>(h->size()));
      for (std::size_t k = 0; k < h->size(); ++k) counts.mutable_at(static_cast<py::ssize_t>(k)) = (*h)[k];
      value = counts;
    } else if (const auto* b = std::get_if<pl::BlobList>(&v)) {
      value = blob_table(runner_->frames() - 1, *b);
    }
    out[py::str(names[i])] = value;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Stream

Stream::Stream(StreamConfig config, py::iterator frames) : config_(std::move(config)), frames_(std::move(frames)) {
  // A user's graph is checked now, before any frame is read; the built-in one is made when the first
  // frame says whether frames are gray or colour, so that neither kind is converted.
  if (config_.spec) {
    std::size_t ignored = 0;
    (void)compile_blob_graph(*config_.spec, ignored);
  }
  load_calibration();
}

Stream::Stream(StreamConfig config, const std::vector<std::string>& inputs) : config_(std::move(config)) {
  // As `neopipe run` reads them: gray (a video's luma plane) for the built-in graph, else the
  // format the graph's source takes, so the tables are the CLI's. In the CLI's order: graph,
  // source, calibration, so that the same mistakes give the same first error.
  pl::PortType want = pl::PortType::gray8;
  if (config_.spec) {
    std::size_t ignored = 0;
    want = compile_blob_graph(*config_.spec, ignored).source_type();
  }
  file_source_ =
      io::open_frame_source(inputs, want == pl::PortType::bgr8 ? io::ColorFormat::bgr : io::ColorFormat::gray);
  load_calibration();
  // Decoding the next frames overlaps with processing these, as in `neopipe run`.
  prefetch_ = std::make_unique<io::PrefetchingSource>(*file_source_);
  start(want);
}

void Stream::load_calibration() {
  if (config_.calib.empty()) {
    if (config_.height != 0) throw py::value_error("height maps blobs through a calibration: give calib");
    return;
  }
  calibration_ = calib::load_calibration(config_.calib);
  if (config_.height != 0) (void)calib::plane_pose(*calibration_);  // refuses the plane homography now, not per frame
  world_dtype_ = world_blob_dtype();
}

py::array Stream::table(const Result& r) {
  if (!calibration_) return blob_table(r.index, r.blobs);
  const cv::Size made_for = calibration_->image_size;
  if (made_for.area() > 0 && r.size != made_for) {
    throw std::runtime_error(fmt::format("{}: made for {}x{} images, but frame {} of {} is {}x{}", config_.calib,
                                         made_for.width, made_for.height, r.index, description(), r.size.width,
                                         r.size.height));
  }
  std::vector<Eigen::Vector2d> centres;
  centres.reserve(r.blobs.size());
  for (const auto& b : r.blobs) centres.emplace_back(b.wcx, b.wcy);
  std::vector<cv::Point2d> world;
  world.reserve(centres.size());
  for (const auto& w : calib::to_world_at_height(*calibration_, centres, config_.height))
    world.emplace_back(w.x(), w.y());
  return blob_table(r.index, r.blobs, world, world_dtype_);
}

Stream::~Stream() {
  // The executor waits for its frames in flight, which read the arrays this object holds; then the
  // reader thread stops, before the source it reads goes.
  executor_.reset();
  prefetch_.reset();
}

std::string Stream::description() const {
  return file_source_ ? file_source_->description() : "frames from Python";
}

void Stream::start(pl::PortType first_frame_type) {
  pl::GraphSpec spec;
  if (config_.spec) {
    spec = *config_.spec;
  } else {
    pl::BlobGraphOptions o = config_.builtin;
    o.source = first_frame_type;
    spec = pl::blob_graph(o);
  }
  pl::CompiledGraph graph = compile_blob_graph(spec, blob_output_);
  source_type_ = graph.source_type();
  keep_one_more_ = graph.has_delays();
  pl::ExecutorOptions options;
  options.threads = config_.threads;
  // Runs on this thread, inside submit and finish, with the GIL released: no Python here.
  executor_ = std::make_unique<pl::Executor>(std::move(graph), options, [this](pl::FrameResult&& r) {
    delivered_ = r.index;
    results_.push_back({r.index, r.input.size(), std::move(std::get<pl::BlobList>(r.outputs[blob_output_]))});
  });
}

void Stream::release_delivered() {
  // A delayed edge may read the previous frame's source image while this one is processed.
  const std::int64_t keep_from = keep_one_more_ ? delivered_ : delivered_ + 1;
  while (!in_flight_.empty() && in_flight_.front().first < keep_from) in_flight_.pop_front();
}

// Reads one frame and submits it; false at the end of the frames (the rest then delivered).
bool Stream::feed_one() {
  if (file_source_) {
    std::optional<io::SourceFrame> f;
    {
      py::gil_scoped_release release;
      f = prefetch_->next();
      if (f) {
        executor_->submit(next_index_, f->image);
      } else {
        executor_->finish();
      }
    }
    if (!f) return false;
    ++next_index_;
    return true;
  }
  if (*frames_ == py::iterator::sentinel()) {
    if (executor_) {
      py::gil_scoped_release release;
      executor_->finish();
    }
    return false;
  }
  py::object item = py::reinterpret_borrow<py::object>(**frames_);
  ++*frames_;  // the next item is fetched now: errors of the caller's iterable surface here
  if (!py::isinstance<py::array>(item)) {
    throw py::value_error(fmt::format("frame {}: a {}, not a numpy array", next_index_,
                                      std::string(py::str(item.get_type().attr("__name__")))));
  }
  const auto array = py::reinterpret_borrow<py::array>(item);
  const cv::Mat view = frame_view(array, next_index_);
  if (!executor_) start(frame_type(view));
  const cv::Mat input = as_source(view, source_type_);
  in_flight_.emplace_back(next_index_, std::move(item));
  {
    py::gil_scoped_release release;
    try {
      executor_->submit(next_index_, input);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(e.what());  // a frame of another size than the first: the caller's array
    }
  }
  ++next_index_;
  return true;
}

py::array Stream::next() {
  while (results_.empty() && !finished_) {
    try {
      if (!feed_one()) finished_ = true;
    } catch (...) {
      // Rows of the frames processed before the error come out first, as the CLI writes them: the
      // frames still in flight are finished (a second error, the same failure again, is dropped).
      finished_ = true;
      error_ = std::current_exception();
      if (executor_) {
        py::gil_scoped_release release;
        try {
          executor_->finish();
        } catch (...) {
        }
      }
    }
    release_delivered();
  }
  if (results_.empty()) {
    in_flight_.clear();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    throw py::stop_iteration();
  }
  const Result r = std::move(results_.front());
  results_.pop_front();
  return table(r);
}

}  // namespace neopipe::python
