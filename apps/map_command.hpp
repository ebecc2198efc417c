#pragma once
// `neopipe map`: the map-maker. Reads a world (file or calibrated blob table), builds its parkways,
// trajectories and QOC, and with --from/--to plans a route and writes its custom map.

#include <CLI/CLI.hpp>
#include <string>

#include "rig/reports.hpp"

namespace neopipe::apps {

struct MapArgs {
  rig::MapRequest request;  ///< what the map-maker is asked (rig/reports.hpp)
  std::string size;         ///< workspace WxH for --blobs, mm (request.size once parsed)
  bool json = false;
  std::string plot;
  std::string out;  ///< empty: stdout
};

CLI::App* add_map_command(CLI::App& app, MapArgs& args);
int map_command(const MapArgs& args);

}  // namespace neopipe::apps
