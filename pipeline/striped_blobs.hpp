#pragma once
// The blob stage as the executor schedules it: a tall frame is labelled in horizontal stripes on the
// calling task arena's threads and the stripes are joined at their borders (merge_stripes is exact,
// so the table is the one pass's). Short frames are one stripe: there, other frames in flight keep
// the threads busy at less cost. Used by the blobs node, and by the benchmark's Halide composite,
// which keeps neopipe's blob stage.

#include <opencv2/core/mat.hpp>

#include "kernels/blobs.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline {

/// Frames shorter than twice this are labelled in one pass.
inline constexpr int kMinBlobStripeRows = 512;

/// extract_blobs(in, params, weights), in stripes over the current task arena's threads.
BlobList striped_blobs(const cv::Mat& in, const kernels::BlobParams& params, const cv::Mat& weights);

}  // namespace neopipe::pipeline
