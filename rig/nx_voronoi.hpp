#pragma once
// The true Voronoi graph of a world's marbles, computed independently of NX by OpenCV's Delaunay
// subdivision (cv::Subdiv2D's Voronoi facets), and NX's learned map held against it: how far each
// learned place lies from the nearest true vertex, which true vertices and edges it found.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "rig/nx_system.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

struct VoronoiGraph {
  std::vector<Eigen::Vector2d> vertices;                   ///< within the margin around the world
  std::vector<std::pair<std::size_t, std::size_t>> edges;  ///< between two of those vertices
  std::vector<double> edge_clearance;  ///< least gap between an edge and its two marbles' surfaces, mm
};

/// The vertices within `margin_mm` of the world (NX, knowing nothing of the world's edges, follows
/// edges beyond them as far as the arm reaches), and the edges between them. No vertex for fewer
/// than three marbles or marbles all on one line.
VoronoiGraph true_voronoi(const sim::World& world, double margin_mm = 100);

struct VoronoiComparison {
  double match_radius_mm = 3;             ///< a place "finds" the true vertex within this
  std::vector<double> place_errors;       ///< each learned place to its nearest true vertex, mm
  std::vector<std::size_t> place_vertex;  ///< that vertex
  std::size_t true_vertices = 0;
  std::size_t vertices_found = 0;
  std::size_t true_edges = 0;
  std::size_t learned_edges = 0;
  std::size_t edges_found = 0;  ///< learned edges joining the two ends of a true edge
  std::size_t edges_wrong = 0;  ///< learned edges that do not
  /// True edges with both ends found and room to pass (clearance >= 10 mm) that NX did not learn.
  std::size_t edges_missed = 0;
  std::size_t edges_too_narrow = 0;  ///< true edges with both ends found but clearance < 10 mm
  /// Places within the match radius of a true vertex an earlier place already found (a known place
  /// NX failed to recognise).
  std::size_t duplicate_places = 0;
  std::vector<Eigen::Vector2d> places;  ///< where each place really is (the harness's notes)
  /// How far NX's dead-reckoned position of each place is from the truth (both taken relative to
  /// where the exploration's odometry began), mm.
  std::vector<double> odometry_errors;
};

VoronoiComparison compare_with_voronoi(const NxExploration& exploration, const VoronoiGraph& truth,
                                       double match_radius_mm = 3);

nlohmann::json voronoi_comparison_json(const VoronoiComparison& c);

}  // namespace neopipe::rig
