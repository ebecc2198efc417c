#pragma once
// `neopipe map`: the map-maker. Reads a world (file or calibrated blob table), builds its parkways,
// trajectories and QOC, and with --from/--to plans a route and writes its custom map.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace neopipe::apps {

struct MapArgs {
  std::string world;  ///< world YAML (neopipe sim world)
  std::string blobs;  ///< or a blob table with X,Y (neopipe run --calib), first frame
  std::string size;   ///< workspace WxH for --blobs, mm
  double window = 50;
  std::optional<double> margin;
  std::optional<double> sigma;
  double border_tolerance = 0;
  std::string descriptions = "extended";  ///< paper | extended
  std::string calib;                      ///< σ from its held-out error
  double move_error = 0.003;              ///< across-track sd per mm moved
  double rotation_error = 0.002;          ///< heading sd, degrees per mm moved
  std::optional<std::int64_t> from;
  std::optional<std::int64_t> to;
  std::string cost = "ratio";
  double reliable_threshold = 0.9;  ///< edges at least this reliable form the reliable parkway
  bool json = false;
  std::string plot;
  std::string out;  ///< empty: stdout
};

CLI::App* add_map_command(CLI::App& app, MapArgs& args);
int map_command(const MapArgs& args);

}  // namespace neopipe::apps
