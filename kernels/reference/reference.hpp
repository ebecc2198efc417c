#pragma once
// Plain scalar references for every kernel: one pixel at a time, borders through one accessor,
// written for obviousness rather than speed. The tests hold the real kernels to these.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/alu.hpp"
#include "kernels/blobs.hpp"
#include "kernels/bool3x3.hpp"
#include "kernels/conv3x3.hpp"
#include "kernels/convert.hpp"
#include "kernels/histogram.hpp"
#include "kernels/lut.hpp"
#include "kernels/lut2.hpp"
#include "kernels/value_blobs.hpp"

namespace neopipe::kernels::reference {

/// Pixel (x, y) of a one-channel image, or what the border supplies outside it.
int pixel_at(const cv::Mat& img, int x, int y, const Border& border);

cv::Mat lut(const cv::Mat& src, const Lut& table);
cv::Mat threshold(const cv::Mat& src, int t, std::uint8_t high);
cv::Mat alu(AluOp op, const cv::Mat& a, const cv::Mat& b);
cv::Mat lut2(const cv::Mat& a, const cv::Mat& b, const Lut2& table);
cv::Mat bgr_to_gray(const cv::Mat& bgr);
cv::Mat conv3x3(const cv::Mat& src, const Conv3x3& k, int dst_type);
cv::Mat bool3x3(const cv::Mat& src, const Bool3x3& k);
cv::Mat convert_s16(const cv::Mat& src, const ConvertS16& c);
Histogram histogram(const cv::Mat& src);
/// Flood fill from each unlabelled foreground pixel in raster order; stats summed pixel by pixel.
std::vector<Blob> blobs(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights = cv::Mat());
/// Flood fill over equal non-zero values of a CV_16SC1 image, from each unlabelled pixel in raster
/// order. The exact sums go through to_blob, as in the fast path, so the two agree bit for bit
/// when they find the same components.
std::vector<Blob> value_blobs(const cv::Mat& src, Connectivity connectivity);

}  // namespace neopipe::kernels::reference
