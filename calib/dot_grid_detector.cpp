#include "calib/dot_grid_detector.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "calib/dot_grid.hpp"
#include "calib/grid_labelling.hpp"
#include "kernels/threshold.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::calib {
namespace {

// Smaller blobs are sensor noise or specks: a dot this small could not be located to 0.1 px anyway,
// and dropping them keeps a target-less image from handing thousands of specks to the ordering.
constexpr std::int64_t kMinDotArea = 5;
// Where the refining threshold sits between the board's level and the dots' (see find_dot_grid).
constexpr double kRefineFraction = 0.2;
// ... but this many board noise deviations above the board at least, so that noise specks do not
// cling to the dots.
constexpr double kRefineNoiseMargin = 5;
// A refined centroid further than this from the first pass's is not the same dot.
constexpr double kRefineMaxShiftPx = 1.0;

// Levels in "dot" units: the gray level for bright dots, 255 minus it for dark ones, so that dots
// are always above the threshold and the excess over it is the blob weight.
enum class Polarity { bright_dots, dark_dots };

int to_dot_units(int gray, Polarity polarity) {
  return polarity == Polarity::bright_dots ? gray : 255 - gray;
}

// Adds the frame source (and BT.601 gray for BGR frames); returns the node that holds the gray image.
std::string add_gray_source(pipeline::GraphBuilder& b, const cv::Mat& image) {
  if (image.type() == CV_8UC1) {
    b.node("src", "source", "{format: gray}");
    return "src";
  }
  b.node("src", "source", "{format: bgr}").node("gray", "gray").connect("src", "gray.in");
  return "gray";
}

pipeline::Value run_once(const pipeline::GraphBuilder& b, const cv::Mat& image) {
  auto results = pipeline::run_frames(pipeline::compile(b.spec(), pipeline::standard_kernels()), {image});
  return std::move(results.at(0).outputs.at(0));
}

// Otsu's T from the engine's own histogram of the engine's own gray image: exactly the level the
// engine's `threshold: otsu` would choose for this frame (kernels::otsu_threshold computes it as
// cv::threshold does), and for a BGR frame it is taken from the very gray image the blob graph reads.
int otsu_level(const cv::Mat& image) {
  pipeline::GraphBuilder b("<dot grid: histogram>");
  const std::string gray = add_gray_source(b, image);
  b.node("hist", "histogram").connect(gray, "hist.in").output("hist");
  return kernels::otsu_threshold(std::get<pipeline::Histogram>(run_once(b, image)));
}

// The blobs above `t` (dot units), weighted by their excess over t (examples/marbles.yaml's idea):
// the rim pixels, which the threshold cuts arbitrarily, then weigh almost nothing, so the centroid
// does not depend on which of them pass.
std::vector<Dot> find_dots(const cv::Mat& image, int t, Polarity polarity) {
  pipeline::GraphBuilder b("<dot grid: dots>");
  const std::string gray = add_gray_source(b, image);
  const std::string excess =
      polarity == Polarity::bright_dots ? "a - " + std::to_string(t) : std::to_string(255 - t) + " - a";
  b.node("excess", "lut", "{expr: \"" + excess + "\"}");
  b.node("blobs", "blobs", "{threshold: 0, connectivity: 8}");
  b.connect(gray, "excess.in").connect("excess", "blobs.in").connect("excess", "blobs.weights").output("blobs");
  const auto blobs = std::get<pipeline::BlobList>(run_once(b, image));
  std::vector<Dot> dots;
  for (const auto& blob : blobs) {
    // A dot cut by the border has its centroid pulled inwards: better no grid than a wrong point.
    const bool inside =
        blob.x0 > 0 && blob.y0 > 0 && blob.x0 + blob.width < image.cols && blob.y0 + blob.height < image.rows;
    if (inside && blob.area >= kMinDotArea) {
      dots.push_back({Eigen::Vector2d(blob.wcx, blob.wcy), static_cast<double>(blob.area)});
    }
  }
  return dots;
}

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The refining threshold for a grid found in `gray`: the board's level is read between the dots
// (at the middle of each cell of four), the dots' at their centres, both as medians.
int refined_level(const cv::Mat& gray, const std::vector<Eigen::Vector2d>& grid, int cols, int rows,
                  Polarity polarity) {
  const auto level_at = [&](const Eigen::Vector2d& p) {
    const int x = std::clamp(static_cast<int>(std::lround(p.x())), 0, gray.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(p.y())), 0, gray.rows - 1);
    return static_cast<double>(to_dot_units(gray.at<std::uint8_t>(y, x), polarity));
  };
  std::vector<double> dot;
  dot.reserve(grid.size());
  for (const auto& p : grid) dot.push_back(level_at(p));
  std::vector<double> board;
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < cols; ++i) {
      const auto at = [&](int ii, int jj) { return grid[grid_index(ii, jj, cols)]; };
      board.push_back(level_at((at(i, j) + at(i + 1, j) + at(i, j + 1) + at(i + 1, j + 1)) / 4));
    }
  }
  const double board_level = median(board);
  std::vector<double> deviation;
  deviation.reserve(board.size());
  for (const double b : board) deviation.push_back(std::abs(b - board_level));
  const double board_sigma = 1.4826 * median(deviation);  // the MAD as a Gaussian sigma
  const double t =
      board_level + std::max(kRefineFraction * (median(dot) - board_level), kRefineNoiseMargin * board_sigma);
  return static_cast<int>(std::ceil(t));
}

}  // namespace

std::optional<std::vector<Eigen::Vector2d>> find_dot_grid(const cv::Mat& image, int cols, int rows) {
  if (image.type() != CV_8UC1 && image.type() != CV_8UC3) {
    throw std::invalid_argument("find_dot_grid: the image must be 8-bit gray or BGR (CV_8UC1 or CV_8UC3)");
  }
  if (image.empty() || cols < 2 || rows < 2) return std::nullopt;
  // Two passes of the blob graph. Otsu's T, halfway between board and dots, finds the grid reliably
  // whatever else the image holds. But at T the dots' rims lose the pixels less than about half
  // covered, and where the rim is cut depends on how the dot falls on the pixel grid: on rendered
  // targets the centroids scatter by 0.03 px RMS. A threshold a fifth of the way up from the board
  // keeps nearly all of the rim (flat, noiseless: 0.007 px; OpenCV's findCirclesGrid, 0.013 px), and the grid found
  // says where the board and the dots are, so the second pass uses one. Should that pass see the
  // dots merged with each other or with clutter, the first pass's centres stand.
  const int otsu = otsu_level(image);
  const cv::Mat gray = [&] {
    if (image.type() == CV_8UC1) return image;
    cv::Mat g;
    cv::cvtColor(image, g, cv::COLOR_BGR2GRAY);  // bit-exact with the engine's gray node
    return g;
  }();
  for (const Polarity polarity : {Polarity::bright_dots, Polarity::dark_dots}) {
    // Dot units: dark dots are the gray levels <= T, the dark class of Otsu's split.
    const int t = polarity == Polarity::bright_dots ? otsu : 254 - otsu;
    auto grid = order_dot_grid(find_dots(image, t, polarity), cols, rows);
    if (!grid) continue;
    const int refined = refined_level(gray, *grid, cols, rows, polarity);
    if (refined >= t) return grid;
    const std::vector<Dot> dots = find_dots(image, refined, polarity);
    std::vector<Eigen::Vector2d> better;
    for (const auto& p : *grid) {
      const auto nearest = std::min_element(dots.begin(), dots.end(), [&](const Dot& a, const Dot& b) {
        return (a.centre - p).squaredNorm() < (b.centre - p).squaredNorm();
      });
      if (nearest == dots.end() || (nearest->centre - p).norm() > kRefineMaxShiftPx) return grid;
      better.push_back(nearest->centre);
    }
    return better;
  }
  return std::nullopt;
}

}  // namespace neopipe::calib
