#pragma once
// A node is a configured kernel with typed ports: the unit the scheduler runs. The algorithm lives
// in kernels/; a node only binds ports and parameters to it and says how it may be cut up (its
// footprint). The scheduler decides the rest: which stripes, on which threads, which frames at once.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "kernels/types.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline {

struct PortDecl {
  std::string name;
  PortType type;
  bool optional = false;  ///< inputs only: may be left unconnected
};

/// A node's view of one frame: its inputs (computed) and outputs (to fill).
class NodeIO {
 public:
  NodeIO(std::span<const Value* const> inputs, std::span<Value* const> outputs, std::span<const PortDecl> output_decls,
         cv::Size frame_size)
      : in_(inputs), out_(outputs), out_decls_(output_decls), size_(frame_size) {}

  cv::Size frame_size() const { return size_; }
  bool connected(size_t input) const { return in_[input] != nullptr; }
  const Value& in(size_t input) const { return *in_[input]; }
  const cv::Mat& image(size_t input) const { return std::get<cv::Mat>(*in_[input]); }
  template <class T>
  const T& get(size_t input) const {
    return std::get<T>(*in_[input]);
  }

  /// Output image `output`, allocated at the frame size with the port's pixel type.
  cv::Mat& out_image(size_t output) {
    Value& v = *out_[output];
    if (!std::holds_alternative<cv::Mat>(v)) v = cv::Mat();
    auto& m = std::get<cv::Mat>(v);
    m.create(size_, cv_type(out_decls_[output].type));
    return m;
  }
  /// Output `output` as a T (a Histogram or a BlobList), kept from frame to frame for reuse.
  template <class T>
  T& out(size_t output) {
    Value& v = *out_[output];
    if (!std::holds_alternative<T>(v)) v = T{};
    return std::get<T>(v);
  }
  /// Sets output `output` to a value that is not written in place (e.g. an image read-only shared
  /// with someone else).
  void set_out(size_t output, Value v) { *out_[output] = std::move(v); }

 private:
  std::span<const Value* const> in_;
  std::span<Value* const> out_;
  std::span<const PortDecl> out_decls_;
  cv::Size size_;
};

/// Rows of a node's inputs by frame row index, for computing one output row at a time. They may
/// come from whole-frame images or, when the scheduler fuses nodes, from small stripe buffers that
/// hold only the rows the consumer needs.
class RowInputs {
 public:
  virtual ~RowInputs() = default;
  /// Row y (0 <= y < frame height) of input `input`, as raw bytes of the port's pixel type.
  virtual const std::uint8_t* row(size_t input, int y) const = 0;
  template <class T>
  const T* row_as(size_t input, int y) const {
    return reinterpret_cast<const T*>(row(input, y));  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  }
};

/// Whether the scheduler may run a node on several frames at once.
///  - in_order: one frame at a time, in frame order, like a PIPE stage. Needed by a node that keeps
///    per-frame state in itself (set in begin_frame, read in run_rows) or across frames.
///  - any: the node keeps no state of its own; each frame's work depends only on its inputs, so
///    frames may overlap and a slow node (blob extraction) does not cap the pipeline's throughput.
/// Either way a frame's result is the same: this only widens what may run concurrently.
enum class FrameOrder { in_order, any };

class Node {
 public:
  Node(std::vector<PortDecl> inputs, std::vector<PortDecl> outputs, kernels::Footprint footprint,
       FrameOrder order = FrameOrder::in_order)
      : inputs_(std::move(inputs)), outputs_(std::move(outputs)), footprint_(footprint), order_(order) {}
  virtual ~Node() = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  const std::vector<PortDecl>& inputs() const { return inputs_; }
  const std::vector<PortDecl>& outputs() const { return outputs_; }
  kernels::Footprint footprint() const { return footprint_; }
  FrameOrder frame_order() const { return order_; }

  /// Once, before the first frame. Throws std::invalid_argument if the node cannot run at this
  /// frame size (e.g. a constant image of another size).
  virtual void configure(cv::Size frame_size) { (void)frame_size; }

  /// Once per frame, before any rows. The default allocates the image outputs. Nodes with a frame
  /// footprint do all their work here; point and 3x3 nodes may do whole-frame preparation (Otsu's
  /// histogram). A FrameOrder::in_order node runs one frame at a time, in frame order, so per-frame
  /// members set here are safe to read from run_rows.
  virtual void begin_frame(NodeIO& io);

  /// Computes output rows [rows.start, rows.end). The scheduler calls it for stripes that cover the
  /// frame, possibly at once on several threads: write only these rows. The default computes them
  /// one by one with compute_row, reading the inputs' whole-frame images.
  virtual void run_rows(NodeIO& io, cv::Range rows) const;

  /// The row form of a point or 3x3 node: writes output row y (`width` pixels) into `out`, reading
  /// rows y - halo .. y + halo of its inputs through `in`. The node applies its own vertical border,
  /// so it never asks for a row outside the frame. Nodes with a frame footprint have no row form.
  virtual void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const;

  /// True when compute_row needs nothing that begin_frame prepares from whole input frames (Otsu's
  /// threshold needs its input's histogram first). The scheduler may then fuse the node with its
  /// producer and consumer: run the chain stripe by stripe through small buffers, so intermediate
  /// images never exist whole and stay in cache; begin_frame is then not called for absorbed nodes.
  virtual bool fusable() const { return false; }

 private:
  std::vector<PortDecl> inputs_;
  std::vector<PortDecl> outputs_;
  kernels::Footprint footprint_;
  FrameOrder order_;
};

}  // namespace neopipe::pipeline
