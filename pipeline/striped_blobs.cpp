#include "pipeline/striped_blobs.hpp"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <vector>

namespace neopipe::pipeline {

BlobList striped_blobs(const cv::Mat& in, const kernels::BlobParams& params, const cv::Mat& weights) {
  const int stripes = std::min(tbb::this_task_arena::max_concurrency(), in.rows / kMinBlobStripeRows);
  if (stripes < 2) return kernels::extract_blobs(in, params, weights);
  std::vector<kernels::BlobStripe> parts(static_cast<size_t>(stripes));
  tbb::parallel_for(0, stripes, [&](int i) {
    const cv::Range rows(in.rows * i / stripes, in.rows * (i + 1) / stripes);
    parts[static_cast<size_t>(i)] = kernels::label_stripe(in, params, weights, rows);
  });
  return kernels::merge_stripes(std::move(parts), params);
}

}  // namespace neopipe::pipeline
