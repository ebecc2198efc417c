#include "calib/points_csv.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace neopipe::calib {
namespace {

std::vector<std::string> split(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t");
    const auto e = cell.find_last_not_of(" \t");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}

}  // namespace

Correspondences read_points_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CalibrationError(path + ": cannot be read");
  std::string line;
  if (!std::getline(in, line)) throw CalibrationError(path + ": empty (expected a header with u,v,X,Y)");
  const auto header = split(line);
  std::array<int, 4> column{-1, -1, -1, -1};
  const std::array<std::string, 4> names{"u", "v", "X", "Y"};
  for (std::size_t c = 0; c < header.size(); ++c) {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (header[c] == names[k]) column[k] = static_cast<int>(c);
    }
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (column[k] < 0)
      throw CalibrationError(fmt::format("{}:1: the header has no column '{}' (needs u,v,X,Y)", path, names[k]));
  }
  Correspondences out;
  for (int n = 2; std::getline(in, line); ++n) {
    const auto cells = split(line);
    if (cells.empty() || (cells.size() == 1 && cells[0].empty())) continue;
    std::array<double, 4> v{};
    for (std::size_t k = 0; k < 4; ++k) {
      const auto c = static_cast<std::size_t>(column[k]);
      if (c >= cells.size()) throw CalibrationError(fmt::format("{}:{}: too few columns", path, n));
      std::size_t used = 0;
      try {
        v[k] = std::stod(cells[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cells[c].size() || !std::isfinite(v[k])) {
        throw CalibrationError(fmt::format("{}:{}: {} '{}' is not a number", path, n, names[k], cells[c]));
      }
    }
    out.push_back({{v[0], v[1]}, {v[2], v[3]}});
  }
  return out;
}

}  // namespace neopipe::calib
