#include "nav/qualnav/topology/arrangement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>

namespace neopipe::nav::qualnav {
namespace {

// Three landmarks whose sine of the angle at one of them is below this are collinear: their LPB
// lines coincide (positions are micrometres on a workspace of metres, far above this).
constexpr double kCollinearSine = 1e-9;
// Crossings closer than this fraction of the landmarks' extent are one crossing.
constexpr double kCrossingMerge = 1e-9;

double arrangement_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// A crossing of two lines that share no landmark, before the crossings at one point are merged.
struct CrossingCandidate {
  Eigen::Vector2d point;
  std::size_t line_a;
  std::size_t line_b;
};

double line_distance(const LpbLine& line, const Eigen::Vector2d& point) {
  const Eigen::Vector2d d = line.to - line.from;
  return std::abs(arrangement_cross(d, point - line.from)) / d.norm();
}

}  // namespace

Arrangement::Arrangement(std::span<const LandmarkId> ids, std::span<const Eigen::Vector2d> positions)
    : ids_(ids.begin(), ids.end()), positions_(positions.begin(), positions.end()) {
  if (ids.size() != positions.size()) {
    throw std::invalid_argument("orientation regions: " + std::to_string(ids.size()) + " ids for " +
                                std::to_string(positions.size()) + " positions");
  }
  const std::size_t n = ids.size();
  if (n < 2) {
    throw std::invalid_argument("orientation regions need at least two landmarks, got " + std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (ids[i] == ids[j])
        throw std::invalid_argument("orientation regions: landmark " + std::to_string(ids[i]) + " is given twice");
      if ((positions[i] - positions[j]).norm() == 0) {
        throw std::invalid_argument("orientation regions: landmarks " + std::to_string(ids[i]) + " and " +
                                    std::to_string(ids[j]) + " coincide, so they span no LPB");
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Eigen::Vector2d dij = positions[j] - positions[i];
      for (std::size_t k = j + 1; k < n; ++k) {
        const Eigen::Vector2d dik = positions[k] - positions[i];
        if (std::abs(arrangement_cross(dij, dik)) <= kCollinearSine * dij.norm() * dik.norm()) {
          throw std::invalid_argument("orientation regions: landmarks " + std::to_string(ids[i]) + ", " +
                                      std::to_string(ids[j]) + " and " + std::to_string(ids[k]) +
                                      " are collinear, so their LPB lines coincide");
        }
      }
    }
  }
  pairs_ = all_pairs(ids_);
  // Line index of the pair (i, j), i < j, by positions in ids().
  std::vector<std::vector<std::size_t>> line_of(n, std::vector<std::size_t>(n, 0));
  for (std::size_t i = 0, line = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j, ++line) {
      lines_.push_back({pairs_[line], positions_[i], positions_[j]});
      line_of[i][j] = line_of[j][i] = line;
    }
  }
  // Each landmark is a crossing of its n − 1 lines (none other passes through it: no collinear triple).
  if (n >= 3) {
    for (std::size_t i = 0; i < n; ++i) {
      LineCrossing c{positions_[i], {}, ids_[i]};
      for (std::size_t j = 0; j < n; ++j) {
        if (j != i) c.lines.push_back(line_of[i][j]);
      }
      std::sort(c.lines.begin(), c.lines.end());
      crossings_.push_back(std::move(c));
    }
  }
  // Lines of four distinct landmarks cross away from them, unless parallel.
  std::vector<CrossingCandidate> candidates;
  const std::size_t line_count = lines_.size();
  std::vector<std::pair<std::size_t, std::size_t>> ends(line_count);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) ends[line_of[i][j]] = {i, j};
  }
  // Lines through one landmark meet only there; elsewhere two crossings close together that would
  // put two such lines through one point are distinct (a nearly collinear triple), not one.
  const auto shares_landmark = [&](std::size_t a, std::size_t b) {
    return a != b && (ends[a].first == ends[b].first || ends[a].first == ends[b].second ||
                      ends[a].second == ends[b].first || ends[a].second == ends[b].second);
  };
  for (std::size_t a = 0; a < line_count; ++a) {
    const Eigen::Vector2d da = lines_[a].to - lines_[a].from;
    for (std::size_t b = a + 1; b < line_count; ++b) {
      if (shares_landmark(a, b)) continue;
      const Eigen::Vector2d db = lines_[b].to - lines_[b].from;
      const double denominator = arrangement_cross(da, db);
      if (std::abs(denominator) <= kCollinearSine * da.norm() * db.norm()) continue;  // parallel
      const double t = arrangement_cross(lines_[b].from - lines_[a].from, db) / denominator;
      candidates.push_back({lines_[a].from + t * da, a, b});
    }
  }
  // Merge candidates at one point (three or more lines through it): sorted by x, a window of the
  // merge distance holds every partner.
  Eigen::Vector2d low = positions_.front();
  Eigen::Vector2d high = positions_.front();
  for (const Eigen::Vector2d& p : positions_) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double merge = kCrossingMerge * std::max(1.0, (high - low).maxCoeff());
  std::sort(candidates.begin(), candidates.end(), [](const CrossingCandidate& p, const CrossingCandidate& q) {
    return p.point.x() != q.point.x() ? p.point.x() < q.point.x() : p.point.y() < q.point.y();
  });
  const auto fits = [&](const std::set<std::size_t>& through, const CrossingCandidate& c) {
    return std::none_of(through.begin(), through.end(), [&](std::size_t line) {
      return shares_landmark(line, c.line_a) || shares_landmark(line, c.line_b);
    });
  };
  std::vector<bool> taken(candidates.size(), false);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (taken[i]) continue;
    std::set<std::size_t> through{candidates[i].line_a, candidates[i].line_b};
    for (std::size_t k = i + 1; k < candidates.size() && candidates[k].point.x() - candidates[i].point.x() <= merge;
         ++k) {
      if (!taken[k] && std::abs(candidates[k].point.y() - candidates[i].point.y()) <= merge &&
          fits(through, candidates[k])) {
        taken[k] = true;
        through.insert(candidates[k].line_a);
        through.insert(candidates[k].line_b);
      }
    }
    crossings_.push_back({candidates[i].point, std::vector<std::size_t>(through.begin(), through.end()), std::nullopt});
  }
}

std::size_t Arrangement::region_count() const {
  std::size_t r = 1 + lines_.size();
  for (const LineCrossing& c : crossings_) r += c.multiplicity() - 1;
  return r;
}

SignVector Arrangement::signs_at(const Eigen::Vector2d& point, double tolerance) const {
  SignVector signs;
  signs.reserve(lines_.size());
  for (const LpbLine& line : lines_) {
    signs.push_back(static_cast<std::int8_t>(orientation_from_positions(line.from, line.to, point, tolerance)));
  }
  return signs;
}

double Arrangement::distance_to_lines(const Eigen::Vector2d& point, std::span<const std::size_t> skip) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
    nearest = std::min(nearest, line_distance(lines_[i], point));
  }
  return nearest;
}

std::size_t general_position_region_count(std::size_t n) {
  const auto choose = [](std::size_t m, std::size_t k) {
    if (k > m) return std::size_t{0};
    std::size_t c = 1;
    for (std::size_t i = 1; i <= k; ++i) c = c * (m - k + i) / i;
    return c;
  };
  if (n < 2) return 1;
  return 1 + choose(n, 2) + n * (n - 2) + 3 * choose(n, 4);
}

OrientationRegions::OrientationRegions(const Arrangement& arrangement) : arrangement_(&arrangement) {
  const std::span<const LpbLine> lines = arrangement.lines();
  const std::span<const LineCrossing> crossings = arrangement.crossings();
  // Extent of the picture: rays reach this far past their last crossing.
  double extent = 1;
  for (const Eigen::Vector2d& p : arrangement.positions()) extent = std::max(extent, p.cwiseAbs().maxCoeff());

  if (crossings.empty()) {
    // One line (two landmarks): its two sides.
    const LpbLine& line = lines.front();
    const Eigen::Vector2d d = (line.to - line.from).normalized();
    const Eigen::Vector2d normal(-d.y(), d.x());
    for (const double side : {1.0, -1.0})
      add_region(arrangement.signs_at(line.from + side * extent * normal), line.from + side * extent * normal);
    adjacency_.push_back({0, 1, 0});
    edge_count_ = 1;
    return;
  }

  // Cells: one point in every wedge between consecutive lines round every crossing, nearer to it
  // than any other line.
  for (const LineCrossing& c : crossings) {
    std::vector<double> angles;
    for (const std::size_t i : c.lines) {
      const Eigen::Vector2d d = lines[i].to - lines[i].from;
      const double a = std::atan2(d.y(), d.x());
      angles.push_back(a);
      angles.push_back(a + (a < 0 ? std::numbers::pi : -std::numbers::pi));
    }
    std::sort(angles.begin(), angles.end());
    const double reach = 0.5 * arrangement.distance_to_lines(c.point, c.lines);
    const double radius = std::isfinite(reach) ? reach : extent;
    for (std::size_t k = 0; k < angles.size(); ++k) {
      const double next = k + 1 < angles.size() ? angles[k + 1] : angles.front() + 2 * std::numbers::pi;
      const double middle = 0.5 * (angles[k] + next);
      const Eigen::Vector2d inside = c.point + radius * Eigen::Vector2d(std::cos(middle), std::sin(middle));
      add_region(arrangement.signs_at(inside), inside);
    }
  }

  // Edges: each line cut at its crossings; a point just off either side of each piece names the two
  // regions that share it.
  std::vector<std::vector<double>> cuts(lines.size());
  for (const LineCrossing& c : crossings) {
    for (const std::size_t i : c.lines) {
      const Eigen::Vector2d d = lines[i].to - lines[i].from;
      cuts[i].push_back((c.point - lines[i].from).dot(d) / d.squaredNorm());
    }
  }
  std::set<RegionAdjacency> adjacent;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::vector<double>& t = cuts[i];
    std::sort(t.begin(), t.end());
    const Eigen::Vector2d d = lines[i].to - lines[i].from;
    const Eigen::Vector2d normal = Eigen::Vector2d(-d.y(), d.x()).normalized();
    const double beyond = 2 * extent / d.norm() + 1;
    std::vector<double> middles;
    middles.push_back(t.front() - beyond);
    for (std::size_t k = 0; k + 1 < t.size(); ++k) middles.push_back(0.5 * (t[k] + t[k + 1]));
    middles.push_back(t.back() + beyond);
    edge_count_ += middles.size();
    const std::size_t skip[] = {i};
    for (const double m : middles) {
      const Eigen::Vector2d on = lines[i].from + m * d;
      const double off = 0.5 * arrangement.distance_to_lines(on, skip);
      const auto a = region_with(arrangement.signs_at(on + off * normal));
      const auto b = region_with(arrangement.signs_at(on - off * normal));
      if (!a || !b) {
        throw std::logic_error("orientation regions: a side of LPB (" + std::to_string(lines[i].pair.first) + ", " +
                               std::to_string(lines[i].pair.second) + ") lies in no cell found at a crossing");
      }
      adjacent.insert({std::min(*a, *b), std::max(*a, *b), i});
    }
  }
  adjacency_.assign(adjacent.begin(), adjacent.end());
}

std::size_t OrientationRegions::add_region(const SignVector& signs, const Eigen::Vector2d& interior) {
  const auto [it, fresh] = index_.emplace(signs, regions_.size());
  if (fresh) regions_.push_back({signs, interior});
  return it->second;
}

std::size_t OrientationRegions::euler_region_count() const {
  if (arrangement_->crossings().empty()) return 2;
  return edge_count_ - arrangement_->crossings().size() + 1;
}

std::optional<std::size_t> OrientationRegions::region_of(const Eigen::Vector2d& point) const {
  const SignVector signs = arrangement_->signs_at(point);
  if (std::find(signs.begin(), signs.end(), std::int8_t{0}) != signs.end()) return std::nullopt;
  return region_with(signs);
}

std::optional<std::size_t> OrientationRegions::region_with(const SignVector& signs) const {
  const auto it = index_.find(signs);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

}  // namespace neopipe::nav::qualnav
