#include "sim/jpeg_loss.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace neopipe::sim {
namespace {

// ITU T.81 Annex K, table K.1: luminance quantisation, row-major.
constexpr std::array<int, 64> kLuminance{16, 11, 10, 16, 24,  40,  51,  61,  12, 12, 14, 19, 26,  58,  60,  55,
                                         14, 13, 16, 24, 40,  57,  69,  56,  14, 17, 22, 29, 51,  87,  80,  62,
                                         18, 22, 37, 56, 68,  109, 103, 77,  24, 35, 55, 64, 81,  104, 113, 92,
                                         49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};

}  // namespace

cv::Mat jpeg_loss(const cv::Mat& gray, int quality) {
  if (gray.type() != CV_8UC1) throw std::invalid_argument("jpeg_loss: the image must be 8-bit gray");
  if (quality < 1 || quality > 100) {
    throw std::invalid_argument("jpeg quality " + std::to_string(quality) + ": must be 1..100");
  }
  // The IJG library's scaling of the table by quality (what cv::imwrite's IMWRITE_JPEG_QUALITY does).
  const int scale = quality < 50 ? 5000 / quality : 200 - 2 * quality;
  cv::Mat q(8, 8, CV_32F);
  for (int i = 0; i < 64; ++i) {
    q.at<float>(i / 8, i % 8) =
        static_cast<float>(std::clamp((kLuminance[static_cast<std::size_t>(i)] * scale + 50) / 100, 1, 255));
  }
  // Edge blocks are completed by repeating the last row and column, as libjpeg does.
  const int w = (gray.cols + 7) / 8 * 8;
  const int h = (gray.rows + 7) / 8 * 8;
  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, 0, h - gray.rows, 0, w - gray.cols, cv::BORDER_REPLICATE);
  cv::Mat level;
  padded.convertTo(level, CV_32F, 1, -128);
  cv::Mat coeffs;
  for (int y = 0; y < h; y += 8) {
    for (int x = 0; x < w; x += 8) {
      cv::Mat block = level(cv::Rect(x, y, 8, 8));
      cv::dct(block, coeffs);
      for (int i = 0; i < 64; ++i) {
        auto& c = coeffs.at<float>(i / 8, i % 8);
        const auto step = q.at<float>(i / 8, i % 8);
        c = std::round(c / step) * step;
      }
      cv::idct(coeffs, block);
    }
  }
  cv::Mat out;
  level(cv::Rect(0, 0, gray.cols, gray.rows)).convertTo(out, CV_8U, 1, 128);
  return out;
}

}  // namespace neopipe::sim
