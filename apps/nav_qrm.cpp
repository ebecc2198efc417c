// `neopipe nav --system qrm`: the qualitative relational map's system (rig/qrm_system.hpp) through
// the same rig as Park & Kender's: the map built by an imaging tour, then one journey or trials
// with the same JSON keys, so the two systems compare on the same worlds, seeds and pairs.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "apps/cli_support.hpp"
#include "apps/nav_command.hpp"
#include "apps/nav_journey_support.hpp"
#include "apps/outcome_table.hpp"
#include "apps/progress.hpp"
#include "nav/qrm/rng.hpp"
#include "pipeline/media/media.hpp"
#include "rig/journey.hpp"
#include "rig/qrm_system.hpp"
#include "rig/seeds.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace q = nav::qrm;
using nlohmann::json;

// The world, the estimated RNG of the built map (grey), the planned route (blue), the tool's true
// track (red) and the landmarks the navigator held (green rings): a PNG.
void write_qrm_plot(const std::string& path, const sim::World& world, const rig::QrmSystem& system,
                    const rig::Plan& plan, const rig::JourneyResult& r) {
  if (std::filesystem::path(path).extension() != ".png") {
    throw UsageError{fmt::format("--plot {}: the QRM plot is a .png", path)};
  }
  constexpr double kScale = 2;  // px per mm
  const cv::Size size(static_cast<int>(world.size.x() * kScale), static_cast<int>(world.size.y() * kScale));
  cv::Mat img(size, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x() * kScale)),
                     static_cast<int>(std::lround((world.size.y() - p.y()) * kScale)));
  };
  for (const q::RngEdge& e : q::estimate_rng(system.map()).edges) {
    cv::line(img, px(world.objects[e.i]), px(world.objects[e.j]), cv::Scalar(200, 200, 200), 1, cv::LINE_AA);
  }
  const std::vector<q::LandmarkId>& route = rig::qrm_route(plan);
  for (std::size_t i = 1; i < route.size(); ++i) {
    cv::line(img, px(world.objects[route[i - 1]]), px(world.objects[route[i]]), cv::Scalar(220, 120, 0), 2,
             cv::LINE_AA);
  }
  for (std::size_t i = 1; i < r.arm.track.size(); ++i) {
    cv::line(img, px(r.arm.track[i - 1]), px(r.arm.track[i]), cv::Scalar(0, 0, 220), 1, cv::LINE_AA);
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
  if (!pipeline::media::write_image(path, img))
    throw std::runtime_error(fmt::format("--plot {}: cannot write the image", path));
}

int qrm_one_journey(const NavArgs& a, const sim::World& world, const rig::QrmSystem& system) {
  PlannedJourney planned = plan_one_journey(a, world, system);
  if (!planned.plan) return kExitUnreachable;
  const std::unique_ptr<rig::Plan>& plan = planned.plan;
  const rig::JourneySettings& journey = planned.settings;
  const std::uint32_t from = plan->start;
  const std::uint32_t to = plan->goal;
  const rig::JourneyResult r = rig::run_journey(system, *plan, world, journey);
  const q::NavigationReport& report = *rig::qrm_report(r.travel);
  if (!a.plot.empty()) write_qrm_plot(a.plot, world, system, *plan, r);
  const json held = held_landmarks_json(r);
  if (a.json) {
    std::cout << json{{"system", "qrm"},
                      {"from", from},
                      {"to", to},
                      {"planned_route", rig::qrm_route(*plan)},
                      {"first_route", report.first_route},
                      {"reached", report.reached},
                      {"held", held},
                      {"outcome", rig::outcome_name(r.outcome)},
                      {"reached_goal", rig::reached_goal(r.outcome)},
                      {"ending", q::navigation_ending_name(report.ending)},
                      {"reason", r.travel.reason},
                      {"steps", report.steps},
                      {"detours", report.detours},
                      {"replans", report.replans},
                      {"reroutes", report.reroutes},
                      {"images_fused", report.images_fused},
                      {"frames", r.frames},
                      {"commanded_travel", r.arm.commanded_travel},
                      {"arm_travel", r.arm.true_travel},
                      {"refused_moves", r.arm.refused_moves},
                      {"seed", a.seed}}
                     .dump()
              << '\n';
    return kExitOk;
  }
  const auto ids = [](const auto& v) { return fmt::format("{}", fmt::join(v, " -> ")); };
  std::cout << fmt::format("route {} -> {} on the built map: {}\n", from, to, ids(rig::qrm_route(*plan)))
            << fmt::format("landmarks held: {}\n", ids(report.reached))
            << fmt::format("outcome: {} (navigator: {}{}{})\n", rig::outcome_name(r.outcome),
                           q::navigation_ending_name(report.ending), r.travel.reason.empty() ? "" : ", ",
                           r.travel.reason)
            << fmt::format("{} steps ({} detours), {} re-plans ({} re-routes), {} images fused, {} frames\n",
                           report.steps, report.detours, report.replans, report.reroutes, report.images_fused, r.frames)
            << fmt::format("commanded travel {:.1f} mm, arm travel {:.1f} mm\n", r.arm.commanded_travel,
                           r.arm.true_travel);
  return kExitOk;
}

// The pairs of a trials JSON (`neopipe nav --trials N --json` of either system), planned by QRM.
std::vector<std::unique_ptr<rig::Plan>> plans_for_pairs(const std::string& path, const rig::QrmSystem& system,
                                                        std::size_t objects) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("--pairs {}: cannot open", path));
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("journeys") || !j["journeys"].is_array()) {
    throw std::runtime_error(fmt::format("--pairs {}: not a trials JSON (no \"journeys\" list)", path));
  }
  std::vector<std::unique_ptr<rig::Plan>> plans;
  for (const json& t : j["journeys"]) {
    if (!t.contains("from") || !t.contains("to") || !t["from"].is_number_unsigned() || !t["to"].is_number_unsigned()) {
      throw std::runtime_error(fmt::format("--pairs {}: journey {} has no from/to ids", path, plans.size()));
    }
    const auto from = t["from"].get<std::uint32_t>();
    const auto to = t["to"].get<std::uint32_t>();
    if (from >= objects || to >= objects || from == to) {
      throw std::runtime_error(
          fmt::format("--pairs {}: journey {} ({} -> {}) does not fit this world", path, plans.size(), from, to));
    }
    try {
      plans.push_back(system.plan(from, to));
    } catch (const rig::UnreachableGoal& e) {
      throw std::runtime_error(fmt::format("--pairs {}: journey {}: {}", path, plans.size(), e.what()));
    }
  }
  if (plans.empty()) throw std::runtime_error(fmt::format("--pairs {}: no journeys", path));
  return plans;
}

int qrm_trials(const NavArgs& a, const sim::World& world, const rig::QrmSystem& system) {
  const std::vector<std::unique_ptr<rig::Plan>> plans =
      a.pairs.empty() ? rig::draw_plans(system, world.objects.size(), *a.trials, a.seed)
                      : plans_for_pairs(a.pairs, system, world.objects.size());
  ProgressBar bar("nav", std::ssize(plans), true);
  const rig::TrialsSummary t = rig::run_trials(system, plans, world, arm_journey_settings(a), a.threads,
                                               [&](std::int64_t done) { bar.update(done); });
  bar.clear();
  json j = rig::qrm_trials_json(system, plans, t);
  j["world"] = a.world;
  if (!a.pairs.empty()) j["pairs"] = a.pairs;
  j["seed"] = a.seed;
  j["sigma_move"] = a.sigma_move;
  j["sigma_rot"] = a.sigma_rot;
  if (a.json) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  std::cout << fmt::format(
      "{} journeys on {} ({} objects), system qrm ({} imaging positions, k {}), move {} /mm, rotation {} deg/mm, "
      "seed {}\n\n{:<20} {:>7} {:>8}  {}\n",
      n, a.world, world.objects.size(), a.images, a.k, a.sigma_move, a.sigma_rot, a.seed, "OUTCOME", "COUNT", "RATE",
      "95% CI");
  print_outcome_rows(std::cout, t, n);
  std::cout << "\nthe navigator's endings:";
  for (const auto& [name, count] : j["qrm"]["endings"].items())
    std::cout << fmt::format(" {} {}", name, count.get<std::int64_t>());
  std::cout << fmt::format("\nframes {} in {:.2f} s; mean arm travel {:.1f} mm\n", t.frames, t.seconds,
                           j["mean_arm_travel"].get<double>());
  return kExitOk;
}

}  // namespace

int qrm_nav_command(const NavArgs& a) {
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (static_cast<int>(a.from.has_value()) + static_cast<int>(a.trials.has_value()) +
          static_cast<int>(!a.pairs.empty()) !=
      1) {
    throw UsageError{"give one of --from I --to J (one journey), --trials N (random journeys) or --pairs FILE"};
  }
  if (a.trials && *a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", *a.trials)};
  if (!a.from && !a.plot.empty()) throw UsageError{"--plot draws one journey: use it with --from/--to"};
  if (!a.from && a.as_trial) throw UsageError{"--as-trial replays one journey: give --from/--to"};
  if (!a.diagram.empty()) throw UsageError{"--reliability-diagram is Park & Kender's: QRM makes no forecast"};
  if (!a.video.empty()) throw UsageError{"--video is Park & Kender's onboard view"};
  if (a.images < 1) throw UsageError{fmt::format("--images {}: must be at least 1", a.images)};
  if (a.k < 3) throw UsageError{fmt::format("--k {}: a triple needs at least 3 landmarks", a.k)};
  if (!(a.sigma_move >= 0) || !(a.sigma_rot >= 0) || !std::isfinite(a.sigma_move) || !std::isfinite(a.sigma_rot)) {
    throw UsageError{"--sigma-move and --sigma-rot must be finite and not negative"};
  }
  const sim::World world = sim::load_world(a.world);
  if (world.objects.size() < 3) {
    throw std::runtime_error(
        fmt::format("{}: QRM needs at least three marbles, the world has {}", a.world, world.objects.size()));
  }
  rig::QrmSettings settings;
  settings.images = static_cast<std::size_t>(a.images);
  settings.seed = a.seed;
  settings.navigator.marble_radius_mm = world.marble_diameter / 2;
  settings.navigator.observation.nearest = static_cast<std::size_t>(a.k);
  ProgressBar bar("nav: imaging tour", a.images, true);
  nav::qrm::RelationalMap map = rig::build_map_by_tour(
      world, settings, nullptr, [&](std::size_t done) { bar.update(static_cast<std::int64_t>(done)); });
  bar.clear();
  const rig::QrmSystem system(world, std::move(map), settings);
  return a.from ? qrm_one_journey(a, world, system) : qrm_trials(a, world, system);
}

}  // namespace neopipe::apps
