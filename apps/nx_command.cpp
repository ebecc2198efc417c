#include "apps/nx_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/cli_support.hpp"
#include "apps/nx_plot.hpp"
#include "apps/progress.hpp"
#include "rig/nx_system.hpp"
#include "rig/nx_voronoi.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {

CLI::App* add_nx_command(CLI::App& app, NxArgs& a) {
  CLI::App* nx = app.add_subcommand("nx", "NX in the dots world (qualnav.md §9): the range ring, places, edges");
  nx->require_subcommand(1);
  CLI::App* explore = nx->add_subcommand(
      "explore", "NX explores a world knowing nothing; its learned map against the true Voronoi graph");
  explore->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  explore->add_option("--seed", a.seed, "Seed of the start and of the sensor's and arm's noise")->capture_default_str();
  explore->add_option("--range-error", a.range_error, "The range ring's relative error bound (0: off)")
      ->capture_default_str();
  explore->add_option("--places", a.places, "Budget: stop after this many places")->capture_default_str();
  explore->add_option("--sigma-move", a.sigma_move, "Arm's translation error, sd mm per mm moved")
      ->capture_default_str();
  explore->add_option("--sigma-rot", a.sigma_rot, "Arm's heading error, sd degrees per mm moved")
      ->capture_default_str();
  explore->add_option("--match-radius", a.match_radius, "A place finds a true vertex within this, mm")
      ->capture_default_str();
  explore->add_flag("--json", a.json, "One JSON object on stdout instead of text");
  explore->add_option("--plot", a.plot, "Draw the learned map over the true Voronoi graph (.png)");
  return nx;
}

int nx_command(const CLI::App& /*nx*/, const NxArgs& a) {
  if (!(a.range_error >= 0 && a.range_error < 1)) {
    throw UsageError{fmt::format("--range-error {}: must lie in [0, 1)", a.range_error)};
  }
  if (a.places < 1) throw UsageError{fmt::format("--places {}: must be at least 1", a.places)};
  if (!(a.sigma_move >= 0) || !(a.sigma_rot >= 0) || !std::isfinite(a.sigma_move) || !std::isfinite(a.sigma_rot)) {
    throw UsageError{"--sigma-move and --sigma-rot must be finite and not negative"};
  }
  if (!(a.match_radius > 0)) throw UsageError{fmt::format("--match-radius {}: must be positive", a.match_radius)};
  const sim::World world = sim::load_world(a.world);
  if (world.objects.size() < 3) {
    throw std::runtime_error(
        fmt::format("{}: NX needs at least three marbles, the world has {}", a.world, world.objects.size()));
  }
  rig::NxSettings s;
  s.seed = a.seed;
  s.range_error = a.range_error;
  s.arm = {a.sigma_move, a.sigma_rot};
  s.explore.max_places = static_cast<std::size_t>(a.places);
  ProgressBar bar("nx explore: places", a.places, true);
  const rig::NxExploration e =
      rig::explore_world(world, s, [&](std::size_t done) { bar.update(static_cast<std::int64_t>(done)); });
  bar.clear();
  const rig::VoronoiGraph truth = rig::true_voronoi(world);
  const rig::VoronoiComparison c = rig::compare_with_voronoi(e, truth, a.match_radius);
  if (!a.plot.empty()) write_nx_plot(a.plot, world, e, &truth, e.track);
  nlohmann::json j = rig::nx_exploration_json(e);
  j["world"] = a.world;
  j["seed"] = a.seed;
  j["range_error"] = a.range_error;
  j["truth"] = rig::voronoi_comparison_json(c);
  if (a.json) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  const auto& t = j["truth"];
  std::cout << fmt::format("NX explored {} ({} marbles), range error {}, seed {}: {}\n", a.world, world.objects.size(),
                           a.range_error, a.seed, e.report.ending)
            << fmt::format(
                   "places {}, edges {} (open {}, blocked {}); arrivals at a known place {} ({} without a free "
                   "edge)\n",
                   e.report.places, e.report.edges, e.report.open_edges, e.report.blocked_edges, e.report.matches,
                   e.report.arrivals_unlinked)
            << fmt::format("places to the true vertices: mean {:.3f} mm, max {:.3f} mm, {} of {} within 2 mm\n",
                           t["mean_place_error_mm"].get<double>(), t["max_place_error_mm"].get<double>(),
                           t["places_within_2mm"].get<std::int64_t>(), e.report.places)
            << fmt::format("true vertices found {} of {}; edges found {}, wrong {}, missed {} (too narrow {})\n",
                           c.vertices_found, c.true_vertices, c.edges_found, c.edges_wrong, c.edges_missed,
                           c.edges_too_narrow)
            << fmt::format("TOUR: {} places, {} paths, {} boundary relations; {} moves, {} frames, {:.0f} mm\n",
                           e.tour_places, e.tour_paths, e.tour_boundary_relations, e.report.moves, e.report.frames,
                           e.report.travelled_mm);
  return kExitOk;
}

}  // namespace neopipe::apps
