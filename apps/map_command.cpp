#include "apps/map_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/map_plot.hpp"
#include "calib/calibration.hpp"
#include "nav/mapmaker/map_maker.hpp"
#include "nav/mapmaker/parkway_quality.hpp"
#include "nav/mapmaker/parkways.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;
using nlohmann::json;

Eigen::Vector2d parse_size(const std::string& text) {
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

mm::Workspace load_workspace(const MapArgs& a) {
  if (a.world.empty() == a.blobs.empty()) throw UsageError{"give exactly one of --world FILE and --blobs FILE"};
  if (!a.world.empty()) {
    sim::World world;
    try {
      world = sim::load_world(a.world);
    } catch (const sim::WorldError& e) {
      throw mm::MapError(e.what());
    }
    mm::Workspace w{world.size, world.objects};
    mm::check_workspace(w, a.world);
    return w;
  }
  mm::Workspace w{a.size.empty() ? Eigen::Vector2d(500, 500) : parse_size(a.size), mm::read_blob_positions(a.blobs)};
  mm::check_workspace(w, a.blobs);
  return w;
}

double sigma_of(const MapArgs& a) {
  if (a.sigma) {
    if (!(*a.sigma >= 0) || !std::isfinite(*a.sigma))
      throw UsageError{fmt::format("--sigma {}: must be >= 0 mm", *a.sigma)};
    return *a.sigma;
  }
  if (!a.calib.empty()) {
    // The map-maker's positions are as good as the calibration's held-out error: the larger axis.
    const calib::Calibration c = calib::load_calibration(a.calib);
    return std::max(c.report.held_out.sd.x(), c.report.held_out.sd.y());
  }
  return mm::NavigatorErrors{}.sigma;
}

const char* kind_of(const mm::Step& s) {
  if (s.slide) return "trajectory";
  if (s.seek == nav::Description::Far) return "far";
  if (s.seek == nav::Description::Near) return "near";
  return s.seek == nav::Description::Obvious ? "obvious" : "isolated";
}

json route_json(const mm::Route& route) {
  json path = json::array();
  path.push_back({{"object", route.start}, {"corner", nav::corner_name(route.start_corner)}, {"kind", "start"}});
  for (const mm::RouteStep& rs : route.steps) {
    const mm::Step& s = rs.step;
    json step = {{"object", s.landmark},
                 {"corner", &rs == &route.steps.back() ? json(nullptr) : json(nav::corner_name(s.adjust))},
                 {"kind", kind_of(s)},
                 {"from", s.from.object},
                 {"from_corner", nav::corner_name(s.from.corner)},
                 {"distance", rs.distance},
                 {"unreliability", s.unreliability()},
                 {"landmark_distance", s.landmark_distance},
                 {"visible", s.visible},
                 {"verification", mm::verifiability_name(rs.check.kind)},
                 {"qoc", rs.check.qoc}};
    if (const auto q = rs.entry.verified_quadrants()) step["quadrants"] = nav::format_quadrants(*q);
    if (s.slide) {
      step["via"] = s.via;
      step["dir"] = nav::direction_name(*s.slide);
      step["via_description"] = nav::description_name(s.seek);
    }
    path.push_back(step);
  }
  json entries = json::array();
  for (const nav::MapEntry& e : route.custom_map.entries) entries.push_back(nav::format_entry(e));
  return {{"from", route.start},
          {"to", route.goal},
          {"cost", mm::criterion_name(route.criterion)},
          {"path", path},
          {"costs",
           {{"D", route.distance},
            {"U", route.unreliability},
            {"D_over_R", route.ratio()},
            {"landmark_distance", route.landmark_distance}}},
          {"custom_map", entries},
          {"custom_map_text", nav::format_custom_map(route.custom_map)}};
}

}  // namespace

CLI::App* add_map_command(CLI::App& app, MapArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "map", "Map-maker: parkways, trajectories, QOC of a world; with --from/--to the best route and its custom map");
  cmd->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)");
  cmd->add_option("--blobs", a.blobs,
                  "Or a blob table with workspace X,Y (neopipe run --calib ... --format csv); its first frame");
  cmd->add_option("--size", a.size, "Workspace WxH in mm for --blobs (default 500x500)");
  cmd->add_option("--window", a.window, "Navigator's view window side a, mm")->capture_default_str();
  cmd->add_option("--margin", a.margin, "Corner margin m, mm (default 0.05 a)");
  cmd->add_option("--sigma", a.sigma, "Position error sd per axis, mm (default: from --calib, else 1)");
  cmd->add_option("--calib", a.calib, "Calibration file (neopipe calibrate): sigma = its held-out sd");
  cmd->add_option("--border-tolerance", a.border_tolerance,
                  "mm: objects this close to a quadrant border may fall either side; verification and recovery "
                  "rules hold both ways (neopipe nav uses 3 sqrt(2) sigma + 0.65)")
      ->capture_default_str();
  cmd->add_option("--descriptions", a.descriptions,
                  "paper: describe landmarks as the paper does (Obvious, Isol); extended: also Far and Near, the "
                  "objects in view farthest from and nearest to the reference")
      ->check(CLI::IsMember({"paper", "extended"}))
      ->capture_default_str();
  cmd->add_option("--move-error", a.move_error, "Navigator's across-track error, sd mm per mm moved")
      ->capture_default_str();
  cmd->add_option("--rotation-error", a.rotation_error, "Navigator's heading error, sd degrees per mm moved")
      ->capture_default_str();
  cmd->add_option("--from", a.from, "Start object id");
  cmd->add_option("--to", a.to, "Goal object id");
  add_cost_option(cmd, a.cost);
  cmd->add_option("--reliable-threshold", a.reliable_threshold,
                  "Selection reliability an edge needs to belong to the reliable parkway")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--json", a.json, "One JSON object on stdout instead of text");
  cmd->add_option("--plot", a.plot, "Draw the world, parkways, trajectories and the route (.png or .svg)");
  cmd->add_option("--out", a.out, "Write the report here instead of stdout");
  return cmd;
}

int map_command(const MapArgs& a) {
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (!(a.window > 0) || !std::isfinite(a.window))
    throw UsageError{fmt::format("--window {}: must be > 0 mm", a.window)};
  const auto check_id = [](const char* option, std::int64_t id) {
    if (id < 0) throw UsageError{fmt::format("{} {}: object ids start at 0", option, id)};
    return static_cast<std::uint32_t>(id);
  };
  mm::Workspace workspace = load_workspace(a);
  const std::string origin = a.world.empty() ? a.blobs : a.world;
  if (workspace.objects.empty()) throw mm::MapError(fmt::format("{}: the world has no objects", origin));
  if (workspace.objects.size() == 1) {
    throw mm::MapError(fmt::format("{}: the world has one object; a map needs at least two", origin));
  }
  if (a.window > std::min(workspace.size.x(), workspace.size.y())) {
    throw mm::MapError(fmt::format("--window {} mm is larger than the {}x{} mm world", a.window, workspace.size.x(),
                                   workspace.size.y()));
  }
  mm::MapMakerOptions options;
  options.window = nav::WindowModel::with_side(a.window);
  if (a.margin) options.window.margin = *a.margin;
  options.errors.sigma = sigma_of(a);
  if (!(a.border_tolerance >= 0) || !std::isfinite(a.border_tolerance))
    throw UsageError{fmt::format("--border-tolerance {}: must be >= 0 mm", a.border_tolerance)};
  options.border_tolerance = a.border_tolerance;
  options.extended_descriptions = a.descriptions == "extended";
  options.errors.translation_per_mm = a.move_error;
  options.errors.rotation_per_mm = a.rotation_error * std::numbers::pi / 180;
  const mm::MapMaker maker(std::move(workspace), options);
  const mm::WorldViews& views = maker.views();

  std::optional<mm::Route> route;
  int exit_code = kExitOk;
  std::string unreachable;
  if (a.from) {
    const std::uint32_t from = check_id("--from", *a.from);
    const std::uint32_t to = check_id("--to", *a.to);
    try {
      route = maker.plan(from, to, *mm::parse_criterion(a.cost));
    } catch (const mm::UnreachableGoal& e) {
      unreachable = e.what();
      exit_code = kExitUnreachable;
    }
  }

  const auto general = mm::general_parkways(views);
  const auto obvious = mm::obvious_parkway(views);
  const auto isolated = mm::isolated_parkway(views);
  const auto& trajectories = maker.steps().trajectories();
  const mm::QualifiedParkways qualified =
      mm::qualify_parkways(mm::parkway_edge_qualities(views, options.errors), a.reliable_threshold);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(isolated.size() + trajectories.size());
  for (const mm::ParkwayEdge& e : isolated) edges.emplace_back(e.from, e.to);
  const std::size_t scc_parkways = mm::strongly_connected_components(views.object_count(), edges).size();
  for (const mm::Trajectory& t : trajectories) edges.emplace_back(t.from.object, t.to);
  const std::size_t scc_with_trajectories = mm::strongly_connected_components(views.object_count(), edges).size();

  std::ostringstream report;
  if (a.json) {
    json j;
    j["objects"] = views.object_count();
    j["window"] = {{"side", options.window.side}, {"margin", options.window.margin}};
    j["sigma"] = options.errors.sigma;
    j["border_tolerance"] = options.border_tolerance;
    j["descriptions"] = a.descriptions;
    j["positions"] = json::array();
    for (std::uint32_t i = 0; i < views.object_count(); ++i) {
      j["positions"].push_back({views.position(i).x(), views.position(i).y()});
    }
    j["parkways"]["general"] = general;
    j["parkways"]["obvious"] = json::array();
    for (const auto& e : obvious) j["parkways"]["obvious"].push_back({e.from, nav::corner_name(e.corner), e.to});
    j["parkways"]["isolated"] = json::array();
    for (const auto& e : isolated) j["parkways"]["isolated"].push_back({e.from, nav::corner_name(e.corner), e.to});
    const auto subgraph_json = [](const mm::ParkwaySubgraph& g) {
      json out = {{"obvious", json::array()}, {"isolated", json::array()}};
      for (const auto& e : g.obvious) out["obvious"].push_back({e.from, nav::corner_name(e.corner), e.to});
      for (const auto& e : g.isolated) out["isolated"].push_back({e.from, nav::corner_name(e.corner), e.to});
      return out;
    };
    j["parkways"]["reliable"] = subgraph_json(qualified.reliable);
    j["parkways"]["reliable"]["threshold"] = a.reliable_threshold;
    j["parkways"]["detectable"] = subgraph_json(qualified.detectable);
    j["parkways"]["recoverable"] = subgraph_json(qualified.recoverable);
    j["qoc"] = json::array();
    for (std::uint32_t i = 0; i < views.object_count(); ++i) j["qoc"].push_back(views.qoc(i));
    j["trajectories"] = json::array();
    for (const mm::Trajectory& t : trajectories) {
      j["trajectories"].push_back({{"from", t.from.object},
                                   {"corner", nav::corner_name(t.from.corner)},
                                   {"via", t.via},
                                   {"dir", nav::direction_name(t.direction)},
                                   {"to", t.to},
                                   {"slide", t.slide}});
    }
    j["strongly_connected"] = {{"parkways", scc_parkways}, {"with_trajectories", scc_with_trajectories}};
    if (route) {
      const json planned = route_json(*route);
      for (const auto& [key, value] : planned.items()) j[key] = value;
    }
    if (!unreachable.empty()) j["unreachable"] = unreachable;
    report << j.dump() << '\n';
  } else {
    report << fmt::format(
        "{} objects, window {} mm (margin {} mm), sigma {:.3f} mm\n"
        "parkways: {} general, {} obvious edges, {} isolated edges; {} trajectories\n"
        "  reliable (R >= {}): {} obvious, {} isolated; error-detectable: {} obvious, {} isolated; "
        "error-recoverable: {} obvious, {} isolated\n"
        "strongly connected components: {} with parkways, {} with trajectories too\n",
        views.object_count(), options.window.side, options.window.margin, options.errors.sigma, general.size(),
        obvious.size(), isolated.size(), trajectories.size(), a.reliable_threshold, qualified.reliable.obvious.size(),
        qualified.reliable.isolated.size(), qualified.detectable.obvious.size(), qualified.detectable.isolated.size(),
        qualified.recoverable.obvious.size(), qualified.recoverable.isolated.size(), scc_parkways,
        scc_with_trajectories);
    if (route) {
      report << fmt::format("\nroute {} -> {} by {}:\n", route->start, route->goal,
                            mm::criterion_name(route->criterion))
             << mm::route_table(*route) << "\ncustom map:\n"
             << nav::format_custom_map(route->custom_map) << '\n';
    }
  }
  if (a.out.empty()) {
    std::cout << report.str() << std::flush;
  } else {
    std::ofstream out(a.out);
    out << report.str();
    if (!out) throw mm::MapError(fmt::format("{}: cannot write the report", a.out));
  }
  if (!a.plot.empty()) write_map_plot(maker, route, a.plot);
  if (!unreachable.empty()) print_error("map", unreachable);
  return exit_code;
}

}  // namespace neopipe::apps
