#pragma once
// What the map-maker knows of the world: the workspace's size and where each object is, in mm
// (x East, y North, from (0,0) to size). An object's id is its index. The map-maker gets these
// from a world file or from a calibrated global-camera frame; it never sees the simulator itself.

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace neopipe::nav::mapmaker {

class MapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Workspace {
  Eigen::Vector2d size{500, 500};
  std::vector<Eigen::Vector2d> objects;
};

/// Throws MapError (prefixed by `origin`) for a workspace the map-maker cannot work in: non-finite
/// or non-positive size, an object off the workspace or not finite, two objects at the same place.
void check_workspace(const Workspace& workspace, const std::string& origin);

/// The objects of a blob table written by `neopipe run --calib` (CSV with a header naming at least
/// the columns frame, X and Y): the X,Y of the first frame's blobs, in table order. Throws MapError
/// naming the file (and the line) for a file that cannot be read, a missing column, a line with
/// another number of fields than the header, or an X,Y that is not a finite number.
std::vector<Eigen::Vector2d> read_blob_positions(const std::string& path);

}  // namespace neopipe::nav::mapmaker
