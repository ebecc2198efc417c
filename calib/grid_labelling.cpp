#include "calib/grid_labelling.hpp"

#include <functional>

namespace neopipe::calib {
namespace {

struct Axes {
  Eigen::Vector2d col = Eigen::Vector2d::Zero();  // mean step to the next column
  Eigen::Vector2d row = Eigen::Vector2d::Zero();  // mean step to the next row
};

Axes axes_of(const std::vector<Eigen::Vector2d>& p, int cols, int rows) {
  Axes a;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const auto at = [&](int ii, int jj) { return p[grid_index(ii, jj, cols)]; };
      if (i + 1 < cols) a.col += at(i + 1, j) - at(i, j);
      if (j + 1 < rows) a.row += at(i, j + 1) - at(i, j);
    }
  }
  return a;
}

}  // namespace

std::vector<Eigen::Vector2d> upright_labelling(const std::vector<Eigen::Vector2d>& points, int cols, int rows) {
  // A candidate relabelling: new (i, j) takes old point source(i, j).
  using Source = std::function<std::pair<int, int>(int, int)>;
  std::vector<Source> candidates{
      [](int i, int j) {
        return std::pair{i, j};
      },
      [&](int i, int j) {
        return std::pair{cols - 1 - i, rows - 1 - j};
      },
      [&](int i, int j) {
        return std::pair{i, rows - 1 - j};
      },  // mirrors: only to undo a mirrored input
      [&](int i, int j) {
        return std::pair{cols - 1 - i, j};
      },
  };
  if (cols == rows) {  // a square grid can also be turned a quarter, either way, mirrored or not
    const int n = cols;
    candidates.emplace_back([n](int i, int j) { return std::pair{j, n - 1 - i}; });
    candidates.emplace_back([n](int i, int j) { return std::pair{n - 1 - j, i}; });
    candidates.emplace_back([](int i, int j) { return std::pair{j, i}; });
    candidates.emplace_back([n](int i, int j) { return std::pair{n - 1 - j, n - 1 - i}; });
  }
  std::vector<Eigen::Vector2d> best;
  double best_score = -2;
  for (const auto& source : candidates) {
    std::vector<Eigen::Vector2d> p(points.size());
    for (int j = 0; j < rows; ++j) {
      for (int i = 0; i < cols; ++i) {
        const auto [si, sj] = source(i, j);
        p[grid_index(i, j, cols)] = points[grid_index(si, sj, cols)];
      }
    }
    const Axes a = axes_of(p, cols, rows);
    const double cross = a.col.x() * a.row.y() - a.col.y() * a.row.x();
    if (cross >= 0) continue;  // mirrored, as seen in the image
    const double score = a.col.normalized().x();
    if (score > best_score) {
      best_score = score;
      best = std::move(p);
    }
  }
  return best.empty() ? points : best;
}

}  // namespace neopipe::calib
