#include "apps/map_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/map_plot.hpp"
#include "nav/mapmaker/map_maker.hpp"
#include "rig/reports.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;
using nlohmann::json;

Eigen::Vector2d parse_world_size(const std::string& text) {
  const auto x = text.find('x');
  double w = 0;
  double h = 0;
  std::istringstream ws(text.substr(0, x));
  std::istringstream hs(x == std::string::npos ? "" : text.substr(x + 1));
  if (x == std::string::npos || !(ws >> w) || !(hs >> h) || !(ws >> std::ws).eof() || !(hs >> std::ws).eof() ||
      !(w > 0) || !(h > 0) || !std::isfinite(w) || !std::isfinite(h)) {
    throw UsageError{fmt::format("--size {}: expected WxH in mm, e.g. 500x500", text)};
  }
  return {w, h};
}

}  // namespace

CLI::App* add_map_command(CLI::App& app, MapArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "map", "Map-maker: parkways, trajectories, QOC of a world; with --from/--to the best route and its custom map");
  cmd->add_option("--world", a.request.world, "World file (YAML, as neopipe sim world writes)");
  cmd->add_option("--blobs", a.request.blobs,
                  "Or a blob table with workspace X,Y (neopipe run --calib ... --format csv); its first frame");
  cmd->add_option("--size", a.size, "Workspace WxH in mm for --blobs (default 500x500)");
  cmd->add_option("--window", a.request.window, "Navigator's view window side a, mm")->capture_default_str();
  cmd->add_option("--margin", a.request.margin, "Corner margin m, mm (default 0.05 a)");
  cmd->add_option("--sigma", a.request.sigma, "Position error sd per axis, mm (default: from --calib, else 1)");
  cmd->add_option("--calib", a.request.calib, "Calibration file (neopipe calibrate): sigma = its held-out sd");
  cmd->add_option("--border-tolerance", a.request.border_tolerance,
                  "mm: objects this close to a quadrant border may fall either side; verification and recovery "
                  "rules hold both ways (neopipe nav uses 3 sqrt(2) sigma + 0.65)")
      ->capture_default_str();
  cmd->add_option("--descriptions", a.request.descriptions,
                  "paper: describe landmarks as the paper does (Obvious, Isol); extended: also Far and Near, the "
                  "objects in view farthest from and nearest to the reference")
      ->check(CLI::IsMember({"paper", "extended"}))
      ->capture_default_str();
  cmd->add_option("--move-error", a.request.move_error, "Navigator's across-track error, sd mm per mm moved")
      ->capture_default_str();
  cmd->add_option("--rotation-error", a.request.rotation_error, "Navigator's heading error, sd degrees per mm moved")
      ->capture_default_str();
  cmd->add_option("--from", a.request.from, "Start object id");
  cmd->add_option("--to", a.request.to, "Goal object id");
  add_cost_option(cmd, a.request.cost);
  cmd->add_option("--reliable-threshold", a.request.reliable_threshold,
                  "Selection reliability an edge needs to belong to the reliable parkway")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--json", a.json, "One JSON object on stdout instead of text");
  cmd->add_option("--plot", a.plot, "Draw the world, parkways, trajectories and the route (.png or .svg)");
  cmd->add_option("--out", a.out, "Write the report here instead of stdout");
  return cmd;
}

int map_command(const MapArgs& a) {
  rig::MapRequest r = a.request;
  if (!a.size.empty()) r.size = parse_world_size(a.size);
  rig::MapReport m;
  try {
    m = rig::map_report(r);
  } catch (const rig::RequestError& e) {
    throw UsageError{e.what()};
  }
  const json& j = m.json;

  std::ostringstream report;
  if (a.json) {
    report << j.dump() << '\n';
  } else {
    const json& p = j["parkways"];
    report << fmt::format(
        "{} objects, window {} mm (margin {} mm), sigma {:.3f} mm\n"
        "parkways: {} general, {} obvious edges, {} isolated edges; {} trajectories\n"
        "  reliable (R >= {}): {} obvious, {} isolated; error-detectable: {} obvious, {} isolated; "
        "error-recoverable: {} obvious, {} isolated\n"
        "strongly connected components: {} with parkways, {} with trajectories too\n",
        j["objects"].get<std::uint32_t>(), j["window"]["side"].get<double>(), j["window"]["margin"].get<double>(),
        j["sigma"].get<double>(), p["general"].size(), p["obvious"].size(), p["isolated"].size(),
        j["trajectories"].size(), r.reliable_threshold, p["reliable"]["obvious"].size(),
        p["reliable"]["isolated"].size(), p["detectable"]["obvious"].size(), p["detectable"]["isolated"].size(),
        p["recoverable"]["obvious"].size(), p["recoverable"]["isolated"].size(),
        j["strongly_connected"]["parkways"].get<std::size_t>(),
        j["strongly_connected"]["with_trajectories"].get<std::size_t>());
    if (m.route) {
      report << fmt::format("\nroute {} -> {} by {}:\n", m.route->start, m.route->goal,
                            mm::criterion_name(m.route->criterion))
             << mm::route_table(*m.route) << "\ncustom map:\n"
             << nav::format_custom_map(m.route->custom_map) << '\n';
    }
  }
  if (a.out.empty()) {
    std::cout << report.str() << std::flush;
  } else {
    std::ofstream out(a.out);
    out << report.str();
    if (!out) throw mm::MapError(fmt::format("{}: cannot write the report", a.out));
  }
  if (!a.plot.empty()) write_map_plot(*m.maker, m.route, a.plot);
  if (!m.unreachable.empty()) {
    print_error("map", m.unreachable);
    return kExitUnreachable;
  }
  return kExitOk;
}

}  // namespace neopipe::apps
