#pragma once
// Graphs neopipe knows without a spec file.

#include <optional>

#include "pipeline/graph_spec.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline {

struct BlobGraphOptions {
  std::optional<int> threshold;      ///< fixed T (value > T is foreground); none = Otsu per frame
  int connectivity = 8;              ///< 4 or 8
  PortType source = PortType::bgr8;  ///< bgr8 frames go through BT.601 gray first
};

/// source -> gray -> threshold -> blobs, the blobs weighted by the gray image. Its output is the
/// blob table "blobs". examples/blobs.yaml is the same graph (with a bgr8 source) as a spec file.
/// `neopipe run` uses a gray8 source unless it annotates (apps/run_command.cpp).
GraphSpec blob_graph(const BlobGraphOptions& options = {});

/// Bright marbles on a dark workspace to a small fraction of a pixel: gray8 source -> excess =
/// gray - `workspace_level` (saturating) -> 8-connected blobs of excess > 0, weighted by the excess,
/// so the rim pixels the cut leaves weigh almost nothing. examples/marbles.yaml is the same graph.
GraphSpec marble_graph(int workspace_level = 60);

/// The panoramic sensor's reading (qualnav.md §2): an s16 ring image of marble discs (value
/// id + 1, background 0) -> 8-connected blobs of equal value. Its output is the blob table "blobs",
/// each blob's value the disc's; a disc cut by the ring's seam is two blobs of one value.
GraphSpec panorama_graph();

}  // namespace neopipe::pipeline
