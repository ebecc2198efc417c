// `neopipe nav --system qualnav`: Qualnav's system (rig/qualnav_system.hpp) through the same rig as
// Park & Kender's and QRM's: a visual memory recorded along each journey's taught route, then one
// journey or trials with the same JSON keys, so the systems compare on the same worlds and seeds.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "apps/cli_support.hpp"
#include "apps/nav_command.hpp"
#include "apps/nav_journey_support.hpp"
#include "apps/outcome_table.hpp"
#include "apps/progress.hpp"
#include "pipeline/media/media.hpp"
#include "rig/journey.hpp"
#include "rig/qualnav_system.hpp"
#include "rig/seeds.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

// --range-error: its default is this system's own.
double qualnav_range_error(const NavArgs& a) {
  return a.range_error.value_or(0.5);
}

namespace qn = nav::qualnav;
using nlohmann::json;

// The world, the taught route (blue) with its recorded viewframes (blue dots), the tool's true
// track (red) and the goal held (green ring): a PNG. A region-level journey also draws the LPB lines
// of its region landmarks (grey: the arrangement of orientation regions, landmarks ringed) and its
// region phase's track in orange.
void write_qualnav_plot(const std::string& path, const sim::World& world, const rig::QualnavPlan& plan,
                        const rig::JourneyResult& r, const qn::NavigationReport& report,
                        const rig::QualnavSettings& settings) {
  constexpr double kScale = 2;  // px per mm
  const cv::Size size(static_cast<int>(world.size.x() * kScale), static_cast<int>(world.size.y() * kScale));
  cv::Mat img(size, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x() * kScale)),
                     static_cast<int>(std::lround((world.size.y() - p.y()) * kScale)));
  };
  for (std::size_t i = 1; i < plan.route.size(); ++i) {
    cv::line(img, px(plan.route[i - 1]), px(plan.route[i]), cv::Scalar(220, 120, 0), 2, cv::LINE_AA);
  }
  for (const Eigen::Vector2d& p : rig::sample_route(plan.route, qn::kViewpathSpacingMm)) {
    cv::circle(img, px(p), 3, cv::Scalar(220, 120, 0), cv::FILLED, cv::LINE_AA);
  }
  std::size_t region_moves = 0;
  if (report.regions.used) {
    region_moves = static_cast<std::size_t>(report.regions.steps);
    const std::vector<qn::LandmarkId> ids =
        qn::region_landmarks(*plan.memory, plan.goal, settings.regions.landmarks, settings.regions.min_range_mm);
    const double reach = world.size.norm();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      for (std::size_t j = i + 1; j < ids.size(); ++j) {
        const Eigen::Vector2d a = world.objects[ids[i]];
        const Eigen::Vector2d d = (world.objects[ids[j]] - a).normalized();
        cv::line(img, px(a - reach * d), px(a + reach * d), cv::Scalar(175, 175, 175), 1, cv::LINE_AA);
      }
    }
    for (const qn::LandmarkId id : ids) {
      cv::circle(img, px(world.objects[id]), 7, cv::Scalar(0, 140, 255), 2, cv::LINE_AA);
    }
  }
  for (std::size_t i = 1; i < r.arm.track.size(); ++i) {
    const cv::Scalar colour = i <= region_moves ? cv::Scalar(0, 140, 255) : cv::Scalar(0, 0, 220);
    cv::line(img, px(r.arm.track[i - 1]), px(r.arm.track[i]), colour, 2, cv::LINE_AA);
  }
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    cv::circle(img, px(world.objects[i]), static_cast<int>(world.marble_diameter * kScale / 2), cv::Scalar(0, 0, 0),
               cv::FILLED, cv::LINE_AA);
    cv::putText(img, std::to_string(i), px(world.objects[i]) + cv::Point(6, -6), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  }
  for (const rig::HeldLandmark& h : r.held) {
    cv::circle(img, px(world.objects[h.actual]), 10, cv::Scalar(0, 160, 0), 2, cv::LINE_AA);
  }
  if (!pipeline::media::write_image(path, img)) {
    throw std::runtime_error(fmt::format("--plot {}: cannot write the image", path));
  }
}

int qualnav_one_journey(const NavArgs& a, const sim::World& world, const rig::QualnavSystem& system) {
  PlannedJourney planned = plan_one_journey(a, world, system);
  if (!planned.plan) return kExitUnreachable;
  const std::unique_ptr<rig::Plan>& plan = planned.plan;
  const rig::JourneySettings& journey = planned.settings;
  const std::uint32_t from = plan->start;
  const std::uint32_t to = plan->goal;
  const rig::JourneyResult r = rig::run_journey(system, *plan, world, journey);
  const qn::NavigationReport& report = *rig::qualnav_report(r.travel);
  const rig::QualnavPlan& p = rig::qualnav_plan(*plan);
  if (!a.plot.empty()) write_qualnav_plot(a.plot, world, p, r, report, system.settings());
  const json held = held_landmarks_json(r);
  const double taught = rig::route_length(p.route);
  if (a.json) {
    std::cout << json{{"system", "qualnav"},
                      {"from", from},
                      {"to", to},
                      {"memory_viewframes", p.memory->nodes().size()},
                      {"taught_route_mm", taught},
                      {"taught_turning_deg",
                       rig::route_turning(rig::sample_route(p.route, qn::kViewpathSpacingMm)) * 180 / std::numbers::pi},
                      {"held", held},
                      {"outcome", rig::outcome_name(r.outcome)},
                      {"reached_goal", rig::reached_goal(r.outcome)},
                      {"ending", qn::navigation_ending_name(report.ending)},
                      {"reason", r.travel.reason},
                      {"steps", report.steps},
                      {"heading_steps", report.heading_steps},
                      {"approach_steps", report.approach_steps},
                      {"replans", report.replans},
                      {"shortcuts", report.shortcuts},
                      {"detours", report.detours},
                      {"path_mm", report.path_mm},
                      {"path_turning_deg", rig::route_turning(rig::sample_route(report.path, qn::kViewpathSpacingMm)) *
                                               180 / std::numbers::pi},
                      {"frames", r.frames},
                      {"commanded_travel", r.arm.commanded_travel},
                      {"arm_travel", r.arm.true_travel},
                      {"refused_moves", r.arm.refused_moves},
                      {"range_error", qualnav_range_error(a)},
                      {"level", rig::qualnav_level_name(system.settings().level)},
                      {"regions", report.regions.used ? rig::qualnav_region_json(report.regions) : json(nullptr)},
                      {"seed", a.seed}}
                     .dump()
              << '\n';
    return kExitOk;
  }
  std::cout << fmt::format("taught route {} -> {}: {:.1f} mm, {} viewframes in memory\n", from, to, taught,
                           p.memory->nodes().size())
            << fmt::format("outcome: {} (navigator: {}{}{})\n", rig::outcome_name(r.outcome),
                           qn::navigation_ending_name(report.ending), r.travel.reason.empty() ? "" : ", ",
                           r.travel.reason)
            << fmt::format("{} steps ({} viewframe heading, {} a heading), {} re-plans, {} shortcuts, {} frames\n",
                           report.steps, report.heading_steps, report.approach_steps, report.replans, report.shortcuts,
                           r.frames)
            << fmt::format(
                   "path {:.1f} mm turning {:.0f} deg (every 20 mm); arm travel {:.1f} mm\n", report.path_mm,
                   rig::route_turning(rig::sample_route(report.path, qn::kViewpathSpacingMm)) * 180 / std::numbers::pi,
                   r.arm.true_travel);
  if (report.regions.used) {
    const qn::RegionLevelCounters& c = report.regions;
    std::cout << fmt::format(
        "region level: {} regions planned, {} crossed, {} shortcuts, {} production steps, {} fallback steps; "
        "phase ended {}{}\n",
        c.plan_regions, c.regions_crossed, c.shortcuts, c.production_steps, c.fallback_steps, c.ending,
        c.fallbacks > 0 ? " (fell back to the viewframe level)" : "");
  }
  return kExitOk;
}

int qualnav_trials(const NavArgs& a, const sim::World& world, const rig::QualnavSystem& system) {
  ProgressBar draw("nav: teaching routes", *a.trials, true);
  const std::vector<std::unique_ptr<rig::Plan>> plans =
      rig::draw_plans(system, world.objects.size(), *a.trials, a.seed);
  draw.clear();
  ProgressBar bar("nav", std::ssize(plans), true);
  const rig::TrialsSummary t = rig::run_trials(system, plans, world, arm_journey_settings(a), a.threads,
                                               [&](std::int64_t done) { bar.update(done); });
  bar.clear();
  json j = rig::qualnav_trials_json(system, plans, t);
  j["world"] = a.world;
  j["seed"] = a.seed;
  j["sigma_move"] = a.sigma_move;
  j["sigma_rot"] = a.sigma_rot;
  if (a.json) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  std::cout << fmt::format(
      "{} journeys on {} ({} objects), system qualnav (level {}, range error {}), move {} /mm, rotation {} deg/mm, "
      "seed {}\n\n"
      "{:<20} {:>7} {:>8}  {}\n",
      n, a.world, world.objects.size(), a.level, qualnav_range_error(a), a.sigma_move, a.sigma_rot, a.seed, "OUTCOME",
      "COUNT", "RATE", "95% CI");
  print_outcome_rows(std::cout, t, n);
  std::cout << "\nthe navigator's endings:";
  for (const auto& [name, count] : j["qualnav"]["endings"].items()) {
    std::cout << fmt::format(" {} {}", name, count.get<std::int64_t>());
  }
  const json& q = j["qualnav"];
  if (q.contains("regions")) {
    const json& g = q["regions"];
    std::cout << fmt::format(
        "\nregion level: {} regions crossed, {} shortcuts, {} production steps, {} fallback steps, {} fallbacks to "
        "the viewframe level; phase endings {}",
        g["regions_crossed"].get<std::int64_t>(), g["shortcuts"].get<std::int64_t>(),
        g["production_steps"].get<std::int64_t>(), g["fallback_steps"].get<std::int64_t>(),
        g["fallbacks"].get<std::int64_t>(), g["phase_endings"].dump());
  }
  std::cout << fmt::format(
      "\narrived: path {:.0f} mm against taught {:.0f} mm; shorter in {}, smoother in {} of {}\n"
      "frames {} in {:.2f} s; mean arm travel {:.1f} mm\n",
      q["arrived_path_mm"].get<double>(), q["arrived_taught_route_mm"].get<double>(),
      q["arrived_shorter_than_taught"].get<std::int64_t>(), q["arrived_smoother_than_taught"].get<std::int64_t>(),
      q["arrived"].get<std::int64_t>(), t.frames, t.seconds, j["mean_arm_travel"].get<double>());
  return kExitOk;
}

}  // namespace

int qualnav_nav_command(const NavArgs& a) {
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (a.from.has_value() == a.trials.has_value()) {
    throw UsageError{"give either --from I --to J (one journey) or --trials N (random journeys)"};
  }
  if (a.trials && *a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", *a.trials)};
  if (!a.from && !a.plot.empty()) throw UsageError{"--plot draws one journey: use it with --from/--to"};
  if (!a.plot.empty() && std::filesystem::path(a.plot).extension() != ".png") {
    throw UsageError{fmt::format("--plot {}: the Qualnav plot is a .png", a.plot)};
  }
  if (!a.from && a.as_trial) throw UsageError{"--as-trial replays one journey: give --from/--to"};
  if (!a.pairs.empty()) throw UsageError{"--pairs goes with --system qrm"};
  if (!a.diagram.empty()) throw UsageError{"--reliability-diagram is Park & Kender's: Qualnav makes no forecast"};
  if (!a.video.empty()) throw UsageError{"--video is Park & Kender's onboard view"};
  if (!(qualnav_range_error(a) >= 0) || !std::isfinite(qualnav_range_error(a))) {
    throw UsageError{fmt::format("--range-error {}: must be finite and not negative (0.5 is the papers' 50 %)",
                                 qualnav_range_error(a))};
  }
  if (!(a.sigma_move >= 0) || !(a.sigma_rot >= 0) || !std::isfinite(a.sigma_move) || !std::isfinite(a.sigma_rot)) {
    throw UsageError{"--sigma-move and --sigma-rot must be finite and not negative"};
  }
  const sim::World world = sim::load_world(a.world);
  if (world.objects.size() < 2) {
    throw std::runtime_error(
        fmt::format("{}: Qualnav needs at least two marbles, the world has {}", a.world, world.objects.size()));
  }
  rig::QualnavSettings settings;
  settings.seed = a.seed;
  settings.sensing.range_error = qualnav_range_error(a);
  settings.detour = a.taught_route == "detour";
  settings.level = a.level == "regions" ? rig::QualnavLevel::regions : rig::QualnavLevel::viewframes;
  const rig::QualnavSystem system(world, settings);
  return a.from ? qualnav_one_journey(a, world, system) : qualnav_trials(a, world, system);
}

}  // namespace neopipe::apps
