// Graph specs: the YAML text through parse_graph_spec and compile (the two halves of loading a
// spec), then, for a spec that compiles, two small frames through the graph, so that parameters
// that pass validation but cannot run are found too. GraphError is the documented failure of all
// three; InlineRunner::run also documents std::invalid_argument for a frame it cannot take.

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/source_location.hpp"

namespace pl = neopipe::pipeline;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pl::KernelRegistry registry = pl::standard_kernels();
  try {
    const pl::GraphSpec spec =
        pl::parse_graph_spec(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml");
    pl::InlineRunner runner(pl::compile(spec, registry));
    // Small and not a multiple of a vector width, so that stripe and tail code both run.
    const int type = runner.graph().source_type() == pl::PortType::bgr8 ? CV_8UC3 : CV_8UC1;
    cv::Mat frame(13, 21, type);
    cv::randu(frame, 0, 256);
    runner.run(frame);
    runner.run(frame);  // the second frame reads the delayed edges' first values
  } catch (const pl::GraphError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
