#include "nav/mapmaker/workspace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

namespace neopipe::nav::mapmaker {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (comma == std::string::npos) return fields;
    begin = comma + 1;
  }
}

}  // namespace

void check_workspace(const Workspace& workspace, const std::string& origin) {
  const Eigen::Vector2d& size = workspace.size;
  if (!(std::isfinite(size.x()) && std::isfinite(size.y()) && size.x() > 0 && size.y() > 0)) {
    throw MapError(fmt::format("{}: workspace size {}x{} must be positive", origin, size.x(), size.y()));
  }
  for (std::size_t i = 0; i < workspace.objects.size(); ++i) {
    const Eigen::Vector2d& p = workspace.objects[i];
    if (!(p.allFinite() && p.x() >= 0 && p.y() >= 0 && p.x() <= size.x() && p.y() <= size.y())) {
      throw MapError(fmt::format("{}: object {} at ({}, {}) lies outside the {}x{} mm workspace", origin, i, p.x(),
                                 p.y(), size.x(), size.y()));
    }
  }
  // Two objects at one place would be one blob to any camera: a corrupt input, not a world.
  std::vector<std::size_t> order(workspace.objects.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto& o = workspace.objects;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return o[a].x() != o[b].x() ? o[a].x() < o[b].x() : (o[a].y() != o[b].y() ? o[a].y() < o[b].y() : a < b);
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (o[order[k]] == o[order[k - 1]]) {
      throw MapError(fmt::format("{}: objects {} and {} are at the same place ({}, {})", origin,
                                 std::min(order[k], order[k - 1]), std::max(order[k], order[k - 1]), o[order[k]].x(),
                                 o[order[k]].y()));
    }
  }
}

std::vector<Eigen::Vector2d> read_blob_positions(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MapError(fmt::format("{}: cannot open the blob table", path));
  std::string line;
  if (!std::getline(in, line)) throw MapError(fmt::format("{}: empty file, expected a blob table", path));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> header = split_csv(line);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) {
      throw MapError(
          fmt::format("{}: no '{}' column; the map-maker needs workspace positions: make the table "
                      "with neopipe run --calib CALIB --format csv",
                      path, name));
    }
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t fx = column("X");
  const std::size_t fy = column("Y");
  const std::size_t ff = column("frame");
  std::vector<Eigen::Vector2d> objects;
  std::string first_frame;
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv(line);
    if (f.size() != header.size()) {
      throw MapError(fmt::format("{}:{}: {} fields, the header has {}", path, number, f.size(), header.size()));
    }
    if (first_frame.empty()) first_frame = f[ff];
    if (f[ff] != first_frame) break;
    double x = 0;
    double y = 0;
    std::istringstream xs(f[fx]);
    std::istringstream ys(f[fy]);
    if (!(xs >> x) || !(ys >> y) || !std::isfinite(x) || !std::isfinite(y)) {
      throw MapError(fmt::format("{}:{}: X,Y '{},{}' are not numbers", path, number, f[fx], f[fy]));
    }
    objects.emplace_back(x, y);
  }
  return objects;
}

}  // namespace neopipe::nav::mapmaker
