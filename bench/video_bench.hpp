#pragma once
// `neopipe bench --video FILE`: how fast `neopipe run` gets through a video (reading plus the graph,
// the results discarded) beside two decode-only rates: cv::VideoCapture reading BGR frames (what a
// user would reach for, issue 3's reference) and neopipe's own reader in the graph's format. All
// three are measured in the same run, interleaved.

#include <cstdint>
#include <opencv2/core/types.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/blob_bench.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::bench {

struct VideoInfo {
  std::string path;
  cv::Size size;
  std::optional<std::int64_t> frames;  ///< as the container declares it
  double fps = 0;                      ///< the video's own rate; 0 if it does not say
};

/// Opens `path` as `neopipe run` does (pipeline::io::open_frame_source) and reads its first frame.
/// Throws io::SourceError naming the file when it is missing, unreadable, an image or a directory
/// rather than a video, or does not decode.
VideoInfo probe_video(const std::string& path, pipeline::io::ColorFormat format);

struct VideoRecord {
  std::string impl;  ///< "opencv_decode", "decode", "run" or "run_csv"
  int threads = 0;
  double fps = 0;  ///< median over the repeats
};

/// Medians over o.repeats of, in this order within each repeat:
///   opencv_decode: cv::VideoCapture(path, CAP_FFMPEG).read() into BGR frames, nothing else;
///   decode:        neopipe's frame source (pipeline::io::open_frame_source) in `format`, nothing else;
///   run:           pipeline::run_stream of `graph` on a fresh source with `threads` workers, in batch
///                  mode, the results discarded;
///   run_csv:       the same, with the blob table formatted as CSV as `neopipe run` writes it (the
///                  bytes are discarded, not a disk's speed): what `neopipe run FILE --out t.csv` costs.
/// Each timed run goes through the file again as often as it takes to last o.min_seconds, and in a
/// long file stops early once they have passed. Opening the file is timed, compiling the graph not.
std::vector<VideoRecord> run_video_bench(const std::string& path, const pipeline::GraphSpec& graph,
                                         pipeline::io::ColorFormat format, int threads, const BenchOptions& o);

}  // namespace neopipe::bench
