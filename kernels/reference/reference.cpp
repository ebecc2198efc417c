#include "kernels/reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <utility>

namespace neopipe::kernels::reference {
namespace {

int round_shift(int acc, int shift) {
  // Halves round toward +infinity: floor(acc / 2^shift + 1/2), computed exactly in floating point.
  return static_cast<int>(std::floor(static_cast<double>(acc) / std::ldexp(1.0, shift) + 0.5));
}

template <class F>
cv::Mat per_pixel(cv::Size size, int type, F f) {
  cv::Mat out(size, type);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const int v = f(x, y);
      if (type == CV_8UC1) {
        out.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
      } else {
        out.at<std::int16_t>(y, x) = static_cast<std::int16_t>(std::clamp(v, -32768, 32767));
      }
    }
  }
  return out;
}

}  // namespace

int pixel_at(const cv::Mat& img, int x, int y, const Border& border) {
  if (x < 0 || y < 0 || x >= img.cols || y >= img.rows) {
    if (border.mode == BorderMode::constant) return border.value;
    x = std::clamp(x, 0, img.cols - 1);
    y = std::clamp(y, 0, img.rows - 1);
  }
  return img.depth() == CV_16S ? img.at<std::int16_t>(y, x) : img.at<std::uint8_t>(y, x);
}

cv::Mat lut(const cv::Mat& src, const Lut& table) {
  return per_pixel(src.size(), CV_8UC1, [&](int x, int y) { return table[src.at<std::uint8_t>(y, x)]; });
}

cv::Mat threshold(const cv::Mat& src, int t, std::uint8_t high) {
  return per_pixel(src.size(), CV_8UC1, [&](int x, int y) { return src.at<std::uint8_t>(y, x) > t ? high : 0; });
}

cv::Mat alu(AluOp op, const cv::Mat& a, const cv::Mat& b) {
  return per_pixel(a.size(), CV_8UC1, [&](int x, int y) {
    const int p = a.at<std::uint8_t>(y, x);
    const int q = b.at<std::uint8_t>(y, x);
    switch (op) {
      case AluOp::add:
        return p + q;  // per_pixel saturates
      case AluOp::sub:
        return p - q;
      case AluOp::absdiff:
        return std::abs(p - q);
      case AluOp::min:
        return std::min(p, q);
      case AluOp::max:
        return std::max(p, q);
      case AluOp::bit_and:
        return p & q;
      case AluOp::bit_or:
        return p | q;
      case AluOp::bit_xor:
        return p ^ q;
    }
    return 0;
  });
}

cv::Mat lut2(const cv::Mat& a, const cv::Mat& b, const Lut2& table) {
  return per_pixel(a.size(), CV_8UC1,
                   [&](int x, int y) { return table(a.at<std::uint8_t>(y, x), b.at<std::uint8_t>(y, x)); });
}

cv::Mat bgr_to_gray(const cv::Mat& bgr) {
  return per_pixel(bgr.size(), CV_8UC1, [&](int x, int y) {
    const auto& p = bgr.at<cv::Vec3b>(y, x);
    // BT.601 in exact rational arithmetic at OpenCV's 15-bit fixed-point weights.
    return static_cast<int>(std::floor((3735.0 * p[0] + 19235.0 * p[1] + 9798.0 * p[2]) / 32768.0 + 0.5));
  });
}

cv::Mat conv3x3(const cv::Mat& src, const Conv3x3& k, int dst_type) {
  return per_pixel(src.size(), dst_type, [&](int x, int y) {
    int acc = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        acc += k.weights[static_cast<size_t>(dy + 1) * 3 + static_cast<size_t>(dx + 1)] *
               pixel_at(src, x + dx, y + dy, k.border);
      }
    }
    return round_shift(acc, k.shift);
  });
}

cv::Mat bool3x3(const cv::Mat& src, const Bool3x3& k) {
  return per_pixel(src.size(), CV_8UC1, [&](int x, int y) {
    unsigned idx = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (pixel_at(src, x + dx, y + dy, k.border) != 0) idx |= 1U << ((dy + 1) * 3 + dx + 1);
      }
    }
    return k.table[idx] ? int{k.high} : 0;
  });
}

cv::Mat convert_s16(const cv::Mat& src, const ConvertS16& c) {
  return per_pixel(src.size(), CV_8UC1, [&](int x, int y) {
    const int v = src.at<std::int16_t>(y, x);
    return round_shift(c.absolute ? std::abs(v) : v, c.shift);
  });
}

Histogram histogram(const cv::Mat& src) {
  Histogram h{};
  for (int y = 0; y < src.rows; ++y) {
    for (int x = 0; x < src.cols; ++x) ++h[src.at<std::uint8_t>(y, x)];
  }
  return h;
}

std::vector<Blob> blobs(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights) {
  const cv::Mat& w = weights.empty() ? src : weights;
  const auto fg = [&](int x, int y) { return int{src.at<std::uint8_t>(y, x)} > params.threshold; };
  cv::Mat label(src.size(), CV_32SC1, cv::Scalar(0));
  std::vector<Blob> out;
  for (int y0 = 0; y0 < src.rows; ++y0) {
    for (int x0 = 0; x0 < src.cols; ++x0) {
      if (!fg(x0, y0) || label.at<int>(y0, x0) != 0) continue;
      const int id = static_cast<int>(out.size()) + 1;
      std::vector<std::pair<int, int>> pixels;
      std::deque<std::pair<int, int>> queue{{x0, y0}};
      label.at<int>(y0, x0) = id;
      while (!queue.empty()) {
        const auto [x, y] = queue.front();
        queue.pop_front();
        pixels.emplace_back(x, y);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || (params.connectivity == Connectivity::four && dx != 0 && dy != 0)) continue;
            const int nx = x + dx;
            const int ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= src.cols || ny >= src.rows) continue;
            if (!fg(nx, ny) || label.at<int>(ny, nx) != 0) continue;
            label.at<int>(ny, nx) = id;
            queue.emplace_back(nx, ny);
          }
        }
      }
      Blob b;
      b.area = static_cast<std::int64_t>(pixels.size());
      int xmin = src.cols, ymin = src.rows, xmax = -1, ymax = -1;
      double sx = 0, sy = 0, sw = 0, swx = 0, swy = 0;
      for (const auto& [x, y] : pixels) {
        xmin = std::min(xmin, x);
        ymin = std::min(ymin, y);
        xmax = std::max(xmax, x);
        ymax = std::max(ymax, y);
        sx += x;
        sy += y;
        const double g = w.at<std::uint8_t>(y, x);
        sw += g;
        swx += g * x;
        swy += g * y;
      }
      b.x0 = xmin;
      b.y0 = ymin;
      b.width = xmax - xmin + 1;
      b.height = ymax - ymin + 1;
      b.cx = sx / static_cast<double>(b.area);
      b.cy = sy / static_cast<double>(b.area);
      b.wcx = sw > 0 ? swx / sw : b.cx;
      b.wcy = sw > 0 ? swy / sw : b.cy;
      for (const auto& [x, y] : pixels) {
        b.mu20 += (x - b.cx) * (x - b.cx);
        b.mu11 += (x - b.cx) * (y - b.cy);
        b.mu02 += (y - b.cy) * (y - b.cy);
      }
      out.push_back(b);
    }
  }
  return out;
}

std::vector<Blob> value_blobs(const cv::Mat& src, Connectivity connectivity) {
  const auto value = [&](int x, int y) { return src.at<std::int16_t>(y, x); };
  cv::Mat label(src.size(), CV_32SC1, cv::Scalar(0));
  std::vector<Blob> out;
  for (int y0 = 0; y0 < src.rows; ++y0) {
    for (int x0 = 0; x0 < src.cols; ++x0) {
      const std::int16_t v = value(x0, y0);
      if (v == 0 || label.at<int>(y0, x0) != 0) continue;
      const int id = static_cast<int>(out.size()) + 1;
      BlobMoments m;
      std::deque<std::pair<int, int>> queue{{x0, y0}};
      label.at<int>(y0, x0) = id;
      while (!queue.empty()) {
        const auto [x, y] = queue.front();
        queue.pop_front();
        m.add_run(y, x, x + 1, 0, 0);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || (connectivity == Connectivity::four && dx != 0 && dy != 0)) continue;
            const int nx = x + dx;
            const int ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= src.cols || ny >= src.rows) continue;
            if (value(nx, ny) != v || label.at<int>(ny, nx) != 0) continue;
            label.at<int>(ny, nx) = id;
            queue.emplace_back(nx, ny);
          }
        }
      }
      Blob b = to_blob(m);
      b.value = v;
      out.push_back(b);
    }
  }
  return out;
}

}  // namespace neopipe::kernels::reference
