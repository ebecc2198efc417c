// Nodes that bring images into the graph: the frame source and a constant image from a file.

#include <stdexcept>

#include "pipeline/media/media.hpp"
#include "pipeline/nodes/nodes.hpp"

namespace neopipe::pipeline::nodes {
namespace {

// The frame being processed. The scheduler sets its value; it computes nothing.
class SourceNode final : public Node {
 public:
  explicit SourceNode(PortType format) : Node({}, {{"out", format}}, kernels::Footprint::frame, FrameOrder::any) {}
  void begin_frame(NodeIO&) override {}
};

// A fixed image (a mask, a background) loaded once from a file.
class ImageNode final : public Node {
 public:
  ImageNode(cv::Mat image, PortType format, std::string path)
      : Node({}, {{"out", format}}, kernels::Footprint::frame, FrameOrder::any),
        image_(std::move(image)),
        path_(std::move(path)) {}

  void configure(cv::Size frame_size) override {
    if (image_.size() != frame_size) {
      throw std::invalid_argument("size mismatch: image '" + path_ + "' is " + std::to_string(image_.cols) + "x" +
                                  std::to_string(image_.rows) + " but the frames are " +
                                  std::to_string(frame_size.width) + "x" + std::to_string(frame_size.height));
    }
  }
  // Shared read-only: consumers never write their inputs.
  void begin_frame(NodeIO& io) override { io.set_out(0, image_); }

 private:
  cv::Mat image_;
  std::string path_;
};

PortType format_param(ParamReader& p, const char* fallback) {
  return p.get_choice("format", fallback, {"bgr", "gray"}) == "bgr" ? PortType::bgr8 : PortType::gray8;
}

}  // namespace

void register_io_nodes(KernelRegistry& r) {
  r.add(
      {kSourceKernel, "the frame being processed; params: format (bgr | gray | s16, default bgr)", [](NodeContext& c) {
         // s16 frames (a panoramic sensor's ring image of marble ids) come from memory, never
         // from an image file, so only the source offers them.
         const std::string format = c.params.get_choice("format", "bgr", {"bgr", "gray", "s16"});
         const PortType type = format == "bgr" ? PortType::bgr8 : format == "gray" ? PortType::gray8 : PortType::s16;
         return std::make_unique<SourceNode>(type);
       }});
  r.add({"image", "a constant image from a file; params: path, format (gray | bgr, default gray)",
         [](NodeContext& c) -> std::unique_ptr<Node> {
           const auto path = c.params.get_optional_string("path");
           if (!path) c.params.fail("path", "required: the image file to load");
           const PortType format = format_param(c.params, "gray");
           std::filesystem::path file(*path);
           if (file.is_relative()) file = c.base_dir / file;
           const cv::Mat img = media::read_image(
               file.string(), format == PortType::bgr8 ? media::ImageMode::color : media::ImageMode::gray);
           if (img.empty()) c.params.fail("path", "cannot read '" + file.string() + "' as an image");
           return std::make_unique<ImageNode>(img, format, file.string());
         }});
}

}  // namespace neopipe::pipeline::nodes
