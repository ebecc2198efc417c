#pragma once
// Lossy compression of video frames as a camera's recorder would apply it: what baseline JPEG's
// lossy step does to an 8-bit gray image (8 x 8 blocks, DCT, quantised with JPEG's standard
// luminance table scaled by the IJG quality factor, inverse DCT, rounded). JPEG's entropy coding
// is lossless, so this is the image a JPEG decoder returns, up to its IDCT's rounding (tested
// against OpenCV's libjpeg). Motion JPEG, the frame-grabber codec of many rigs, is this per frame.

#include <opencv2/core/mat.hpp>

namespace neopipe::sim {

/// `gray` (CV_8UC1) after JPEG at `quality` (1..100; std::invalid_argument otherwise).
[[nodiscard]] cv::Mat jpeg_loss(const cv::Mat& gray, int quality);

}  // namespace neopipe::sim
