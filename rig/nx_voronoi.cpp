#include "rig/nx_voronoi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>

#include "sim/panorama.hpp"

namespace neopipe::rig {
namespace {

using Eigen::Vector2d;

// A vertex's key on a grid far finer than any distance that matters (Subdiv2D works in floats).
std::pair<long long, long long> vertex_key(const cv::Point2f& p) {
  return {std::llround(p.x * 1000.0), std::llround(p.y * 1000.0)};
}

double segment_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

VoronoiGraph true_voronoi(const sim::World& world, double margin_mm) {
  VoronoiGraph g;
  if (world.objects.size() < 3) return g;
  const auto margin = static_cast<float>(std::max(world.size.x(), world.size.y()));
  cv::Subdiv2D subdiv(cv::Rect2f(-margin, -margin, static_cast<float>(world.size.x()) + 2 * margin,
                                 static_cast<float>(world.size.y()) + 2 * margin));
  std::vector<cv::Point2f> sites;
  for (const Vector2d& o : world.objects) sites.emplace_back(static_cast<float>(o.x()), static_cast<float>(o.y()));
  subdiv.insert(sites);
  std::vector<std::vector<cv::Point2f>> facets;
  std::vector<cv::Point2f> centers;
  subdiv.getVoronoiFacetList({}, facets, centers);
  const auto inside = [&](const cv::Point2f& p) {
    return p.x >= -margin_mm && p.y >= -margin_mm && p.x <= world.size.x() + margin_mm &&
           p.y <= world.size.y() + margin_mm;
  };
  // A vertex is a corner of at least three facets (the corners that only hull facets share lie near
  // the subdivision's virtual outer points and are no vertex of the marbles).
  std::map<std::pair<long long, long long>, int> corners;
  for (const auto& poly : facets) {
    for (const cv::Point2f& p : poly) ++corners[vertex_key(p)];
  }
  std::map<std::pair<long long, long long>, std::size_t> index;
  for (const auto& poly : facets) {
    for (const cv::Point2f& p : poly) {
      if (corners[vertex_key(p)] >= 3 && inside(p) && index.emplace(vertex_key(p), g.vertices.size()).second) {
        g.vertices.emplace_back(p.x, p.y);
      }
    }
  }
  std::set<std::pair<std::size_t, std::size_t>> edges;
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const auto& poly = facets[f];
    const Vector2d site(centers[f].x, centers[f].y);  // the facet's marble
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const auto a = index.find(vertex_key(poly[k]));
      const auto b = index.find(vertex_key(poly[(k + 1) % poly.size()]));
      if (a == index.end() || b == index.end() || a->second == b->second) continue;
      const auto e = std::minmax(a->second, b->second);
      if (edges.insert(e).second) {
        g.edges.emplace_back(e);
        g.edge_clearance.push_back(segment_distance(site, g.vertices[e.first], g.vertices[e.second]) -
                                   world.marble_diameter / 2);
      }
    }
  }
  return g;
}

VoronoiComparison compare_with_voronoi(const NxExploration& e, const VoronoiGraph& truth, double match_radius_mm) {
  VoronoiComparison c;
  c.match_radius_mm = match_radius_mm;
  c.true_vertices = truth.vertices.size();
  c.true_edges = truth.edges.size();
  std::vector<bool> found(truth.vertices.size(), false);
  std::vector<std::optional<std::size_t>> matched(e.place_truth.size());
  for (std::size_t p = 0; p < e.place_truth.size(); ++p) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_v = 0;
    for (std::size_t v = 0; v < truth.vertices.size(); ++v) {
      const double d = (truth.vertices[v] - e.place_truth[p]).norm();
      if (d < best) {
        best = d;
        best_v = v;
      }
    }
    c.place_errors.push_back(best);
    c.place_vertex.push_back(best_v);
    if (best <= match_radius_mm) {
      if (found[best_v]) ++c.duplicate_places;
      found[best_v] = true;
      matched[p] = best_v;
    }
  }
  c.vertices_found = static_cast<std::size_t>(std::count(found.begin(), found.end(), true));
  c.places = e.place_truth;
  for (std::size_t p = 0; p < e.map.size() && p < e.place_truth.size(); ++p) {
    c.odometry_errors.push_back((e.map.place(p).position - (e.place_truth[p] - e.start)).norm());
  }
  std::set<std::pair<std::size_t, std::size_t>> true_edges(truth.edges.begin(), truth.edges.end());
  std::set<std::pair<std::size_t, std::size_t>> learned;
  for (std::size_t p = 0; p < e.map.size(); ++p) {
    for (const nav::nx::Slot& s : e.map.place(p).slots) {
      if (s.state != nav::nx::SlotState::explored || s.to_place < p) continue;
      ++c.learned_edges;
      if (!matched[p] || !matched[s.to_place]) {
        ++c.edges_wrong;
        continue;
      }
      const auto key = std::minmax(*matched[p], *matched[s.to_place]);
      if (true_edges.contains(key)) {
        ++c.edges_found;
        learned.insert(key);
      } else {
        ++c.edges_wrong;
      }
    }
  }
  for (std::size_t i = 0; i < truth.edges.size(); ++i) {
    const auto& [a, b] = truth.edges[i];
    if (!found[a] || !found[b] || learned.contains(truth.edges[i])) continue;
    ++(truth.edge_clearance[i] >= sim::kMinClearanceMm ? c.edges_missed : c.edges_too_narrow);
  }
  return c;
}

nlohmann::json voronoi_comparison_json(const VoronoiComparison& c) {
  const double max_error = c.place_errors.empty() ? 0 : *std::max_element(c.place_errors.begin(), c.place_errors.end());
  const double mean_error = c.place_errors.empty()
                                ? 0
                                : std::accumulate(c.place_errors.begin(), c.place_errors.end(), 0.0) /
                                      static_cast<double>(c.place_errors.size());
  const double max_odometry =
      c.odometry_errors.empty() ? 0 : *std::max_element(c.odometry_errors.begin(), c.odometry_errors.end());
  nlohmann::json places = nlohmann::json::array();
  for (const Eigen::Vector2d& p : c.places) places.push_back({p.x(), p.y()});
  const auto within = [&](double r) {
    return std::count_if(c.place_errors.begin(), c.place_errors.end(), [&](double d) { return d <= r; });
  };
  return {{"match_radius_mm", c.match_radius_mm},
          {"place_errors_mm", c.place_errors},
          {"max_place_error_mm", max_error},
          {"mean_place_error_mm", mean_error},
          {"places_within_2mm", within(2)},
          {"places_within_match_radius", within(c.match_radius_mm)},
          {"true_vertices", c.true_vertices},
          {"vertices_found", c.vertices_found},
          {"true_edges", c.true_edges},
          {"learned_edges", c.learned_edges},
          {"edges_found", c.edges_found},
          {"edges_wrong", c.edges_wrong},
          {"edges_missed", c.edges_missed},
          {"edges_too_narrow", c.edges_too_narrow},
          {"duplicate_places", c.duplicate_places},
          {"places", places},
          {"odometry_errors_mm", c.odometry_errors},
          {"max_odometry_error_mm", max_odometry}};
}

}  // namespace neopipe::rig
