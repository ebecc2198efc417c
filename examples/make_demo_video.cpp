// Writes the demo video the README's first command runs on: marbles rolling over a dark,
// unevenly lit table, seen by a slightly noisy camera. Usage: make_demo_video OUT.avi [FRAMES]

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

namespace {

struct Marble {
  cv::Point2d p;
  cv::Point2d v;
};

void draw_marble(cv::Mat& img, cv::Point2d c, double r) {
  const int x0 = std::max(0, static_cast<int>(c.x - r - 2));
  const int x1 = std::min(img.cols - 1, static_cast<int>(c.x + r + 2));
  const int y0 = std::max(0, static_cast<int>(c.y - r - 2));
  const int y1 = std::min(img.rows - 1, static_cast<int>(c.y + r + 2));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      // 4x4 supersampling for the disk's coverage of the pixel; a highlight up and to the left.
      double cover = 0;
      for (int sy = 0; sy < 4; ++sy) {
        for (int sx = 0; sx < 4; ++sx) {
          const double dx = x + (sx + 0.5) / 4 - 0.5 - c.x;
          const double dy = y + (sy + 0.5) / 4 - 0.5 - c.y;
          cover += (dx * dx + dy * dy <= r * r) ? 1.0 / 16 : 0.0;
        }
      }
      if (cover <= 0) continue;
      const double d = std::hypot(x - c.x + 0.3 * r, y - c.y + 0.3 * r) / (1.3 * r);
      const double shade = 150 + 100 * std::max(0.0, 1 - d * d);
      auto& px = img.at<cv::Vec3f>(y, x);
      const cv::Vec3f colour(static_cast<float>(shade * 0.85), static_cast<float>(shade * 0.95),
                             static_cast<float>(shade));
      px = px * static_cast<float>(1 - cover) + colour * static_cast<float>(cover);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_demo_video OUT.avi [FRAMES]\n");
    return 2;
  }
  const std::string out = argv[1];
  const int frames = argc > 2 ? std::stoi(argv[2]) : 120;
  const cv::Size size(640, 480);
  const double radius = 9;
  cv::RNG rng(20260101);
  std::vector<Marble> marbles;
  while (marbles.size() < 24) {
    const cv::Point2d p(rng.uniform(30.0, size.width - 30.0), rng.uniform(30.0, size.height - 30.0));
    bool clear = true;
    for (const auto& m : marbles) clear = clear && cv::norm(m.p - p) > 4 * radius;
    if (!clear) continue;
    const double a = rng.uniform(0.0, 2 * CV_PI);
    const double s = rng.uniform(0.5, 3.0);
    marbles.push_back({p, {s * std::cos(a), s * std::sin(a)}});
  }
  cv::VideoWriter writer(out, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30, size, true);
  if (!writer.isOpened()) {
    std::fprintf(stderr, "make_demo_video: cannot write %s\n", out.c_str());
    return 1;
  }
  writer.set(cv::VIDEOWRITER_PROP_QUALITY, 95);
  for (int f = 0; f < frames; ++f) {
    cv::Mat img(size, CV_32FC3);
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) {
        const float light = 35.0F + 25.0F * static_cast<float>(x) / static_cast<float>(size.width) +
                            10.0F * static_cast<float>(y) / static_cast<float>(size.height);
        img.at<cv::Vec3f>(y, x) = cv::Vec3f(light * 0.9F, light, light * 0.8F);
      }
    }
    for (auto& m : marbles) {
      draw_marble(img, m.p, radius);
      m.p += m.v;
      if (m.p.x < radius || m.p.x > size.width - radius) m.v.x = -m.v.x;
      if (m.p.y < radius || m.p.y > size.height - radius) m.v.y = -m.v.y;
    }
    cv::Mat noise(size, CV_32FC3);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 4.0);
    img += noise;
    cv::Mat bgr;
    img.convertTo(bgr, CV_8UC3);
    writer.write(bgr);
  }
  return 0;
}
