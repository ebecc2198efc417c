#pragma once
// The side-by-side benchmark behind `neopipe bench`: a neopipe graph, the same computation as
// OpenCV calls, and the memory-read floor, on the same generated frames, in the same run.

#include <cstdint>
#include <memory>
#include <opencv2/core/types.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/graph_spec.hpp"

namespace neopipe::bench {

/// The cases, in the order `neopipe bench` runs them by default.
inline const std::vector<std::string> case_names{"dots", "dense", "chain"};

/// True for the cases measured against the Halide composite too (the chain, when this build has
/// Halide): the others have no iconic stage before their blob stage (the threshold is folded into it).
bool has_halide_peer(const std::string& case_name);

/// True for the cases whose frames are make_dots_frame's disks (so a blob count and radius apply).
bool uses_dots_frames(const std::string& case_name);

/// The case name of a user's graph (`neopipe bench --graph G.yaml`): the dots frames, converted to
/// the graph's source format, timed against the read floor (there is no general OpenCV translation).
inline const std::string graph_case_name = "graph";

struct BenchCase {
  std::string name;  ///< "dots", "dense", "chain" or graph_case_name
  cv::Size size;
  int threads = 1;
  int blobs = 100;                                   ///< dots and chain: disks drawn (fewer where they do not fit)
  double radius = 0;                                 ///< dots and chain: disk radius; 0: min(w, h) / 80, at least 3
  std::shared_ptr<const pipeline::GraphSpec> graph;  ///< case graph_case_name: the user's graph
};

struct BenchRecord {
  std::string case_name;
  std::string impl;  ///< "neopipe", "opencv", "floor" or "halide" (the chain case's composite)
  int width = 0;
  int height = 0;
  int threads = 0;
  double fps = 0;           ///< median over the repeats
  double mpix_s = 0;        ///< fps * width * height / 1e6
  double ns_per_pixel = 0;  ///< 1e9 / (fps * width * height)
  /// How far the resident set rose above where it stood while this implementation ran its first
  /// timed run (its buffers, the frames it holds in flight, its threads' stacks), in MiB; nullopt
  /// when the system cannot tell (see PeakGrowth).
  std::optional<double> rss_growth_mib;
};

struct BenchOptions {
  double min_seconds = 0.3;  ///< each timed run lasts at least this long
  int repeats = 5;           ///< runs per measurement; the median is reported
  int distinct_frames = 8;   ///< different generated frames cycled through
};

/// Measures one case with every implementation it has (neopipe, opencv, floor; halide for the
/// chain), interleaved.
std::vector<BenchRecord> run_blob_bench(const BenchCase& c, const BenchOptions& o);

struct CrossCheck {
  std::int64_t blobs = 0;  ///< what neopipe found on the case's first frame (a user's graph: -1 without a blob output)
  std::string mismatch;    ///< empty when OpenCV found the same
};

/// Checks that neopipe and OpenCV find the same number of blobs, with the same total area, on the
/// case's first frame, and that the Halide composite (where the case has one) finds exactly
/// neopipe's blob table (a benchmark of two programs that disagree measures nothing). A user's graph
/// is only run once (it has no peer to agree with); its errors are thrown.
CrossCheck cross_check(const BenchCase& c);

/// The chain case's graph, on gray frames: conv3x3 smooth ([1 2 1; 2 4 2; 1 2 1] / 16) -> threshold
/// (value > `threshold`) -> bool3x3 erode -> bool3x3 dilate (a 3x3 opening) -> blobs (8-connected,
/// weighted by the source frame). Output 0 is the blob table "blobs".
pipeline::GraphSpec chain_graph(int threshold);

}  // namespace neopipe::bench
