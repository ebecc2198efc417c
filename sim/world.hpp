#pragma once
// The dots world: a flat workspace in millimetres (x East, y North, from (0,0) to (W,H)) with
// identical marbles lying on it, none on another. An object's id is its index in `objects`.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace neopipe::sim {

/// A world file or a world request that cannot be honoured; the message names the file (with line
/// and column where there is one) and the cause, in one line.
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct World {
  Eigen::Vector2d size{500, 500};        ///< W, H in mm
  double marble_diameter = 5.0;          ///< mm
  std::vector<Eigen::Vector2d> objects;  ///< marble centres, mm
};

/// Reads a world file (YAML: size, objects, optional marble_diameter). Throws WorldError naming the
/// file, line and column for malformed files, objects outside the workspace and overlapping objects.
World load_world(const std::string& path);

/// The first pair (earlier, later) of marbles closer than diameter + min_gap, in insertion order.
std::optional<std::pair<std::size_t, std::size_t>> first_overlap(const World& world, double min_gap);

/// Writes `world` so that load_world reads back exactly the same numbers.
void save_world(const World& world, const std::string& path);

/// Throws WorldError (prefixed by `origin`) if an object lies outside the workspace (its whole disk
/// must lie on it) or two marbles overlap.
void check_world(const World& world, const std::string& origin);

struct WorldRequest {
  int objects = 100;
  Eigen::Vector2d size{500, 500};
  double marble_diameter = 5.0;
  /// Smallest free space between two marbles, mm. The default keeps neighbours apart by about five
  /// pixels of the default global camera, so blur never joins two blobs.
  double min_gap = 3.0;
  std::uint64_t seed = 1;
};

/// Marbles placed one by one uniformly at random, each rejected and redrawn while it would come
/// closer than min_gap to one already placed (random sequential addition). Positions are rounded to
/// micrometres, so the world file holds them exactly. Same request -> same world. Throws WorldError
/// when the marbles cannot fit.
World generate_world(const WorldRequest& request);

}  // namespace neopipe::sim
