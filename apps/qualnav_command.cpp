#include "apps/qualnav_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "apps/chart_colours.hpp"
#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "nav/qualnav/topology/arrangement.hpp"
#include "nav/qualnav/topology/productions.hpp"
#include "pipeline/media/media.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace qn = nav::qualnav;
using nlohmann::json;

// Above this the crossings (3·C(n,4) of them) fill memory and the listing is unreadable.
constexpr std::size_t kMaxRegionLandmarks = 60;

// --landmarks "i,j,...": marble ids of `world`, each once.
std::vector<qn::LandmarkId> qualnav_landmark_ids(const QualnavArgs& a, const sim::World& world) {
  std::vector<qn::LandmarkId> ids;
  if (a.landmarks.empty()) {
    for (qn::LandmarkId i = 0; i < world.objects.size(); ++i) ids.push_back(i);
    return ids;
  }
  std::size_t at = 0;
  while (at <= a.landmarks.size()) {
    const std::size_t comma = std::min(a.landmarks.find(',', at), a.landmarks.size());
    const std::string item = a.landmarks.substr(at, comma - at);
    std::size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || v < 0) {
      throw UsageError{fmt::format("--landmarks {}: expected a comma-separated list of marble ids", a.landmarks)};
    }
    const auto id = static_cast<qn::LandmarkId>(v);
    if (id >= world.objects.size()) {
      throw std::runtime_error(fmt::format("--landmarks {}: {} has {} marbles (ids 0 to {}), no marble {}", a.landmarks,
                                           a.world, world.objects.size(),
                                           static_cast<long long>(world.objects.size()) - 1, id));
    }
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
      throw std::runtime_error(fmt::format("--landmarks {}: marble {} is given twice", a.landmarks, id));
    }
    ids.push_back(id);
    at = comma + 1;
  }
  return ids;
}

json qualnav_crossing_json(const qn::Arrangement& arrangement, const qn::LineCrossing& c) {
  json lines = json::array();
  for (const std::size_t i : c.lines) {
    const qn::LandmarkPair& p = arrangement.pairs()[i];
    lines.push_back({p.first, p.second});
  }
  return json{{"x", c.point.x()},
              {"y", c.point.y()},
              {"multiplicity", c.multiplicity()},
              {"landmark", c.landmark ? json(*c.landmark) : json(nullptr)},
              {"lines", lines}};
}

// The picture: the world's workspace with margins, mm to pixels (y up).
struct RegionsCanvas {
  double scale = 1;
  double pad = 40;
  double top = 0;  ///< world y at the top edge of the drawing area
  int width = 0;
  int height = 0;
  int footer = 60;
  [[nodiscard]] cv::Point2d px(const Eigen::Vector2d& p) const {
    return {pad + p.x() * scale, pad + (top - p.y()) * scale};
  }
  [[nodiscard]] Eigen::Vector2d world_at(double x, double y) const {
    return {(x - pad) / scale, top - (y - pad) / scale};
  }
};

RegionsCanvas regions_canvas(const sim::World& world) {
  RegionsCanvas c;
  constexpr double kSide = 900;
  c.scale = (kSide - 2 * c.pad) / std::max(world.size.x(), world.size.y());
  c.top = world.size.y();
  c.width = static_cast<int>(std::lround(2 * c.pad + world.size.x() * c.scale));
  c.height = static_cast<int>(std::lround(2 * c.pad + world.size.y() * c.scale));
  return c;
}

// Two points of an LPB line far outside the picture (both drawers clip).
std::pair<Eigen::Vector2d, Eigen::Vector2d> regions_line_ends(const qn::LpbLine& line, const sim::World& world) {
  const Eigen::Vector2d d = (line.to - line.from).normalized();
  const double far = 4 * (world.size.x() + world.size.y());
  return {line.from - far * d, line.from + far * d};
}

// A pale colour per region: a hash of its sign vector over the hue circle.
cv::Vec3b region_colour(std::uint64_t hash) {
  hash ^= hash >> 33;
  hash *= 0xff51afd7ed558ccdULL;
  hash ^= hash >> 33;
  const double hue = static_cast<double>(hash % 3600) / 10.0;
  const double lightness = 0.82 + 0.1 * static_cast<double>((hash >> 20) % 100) / 100.0;
  cv::Mat hls(1, 1, CV_32FC3, cv::Scalar(hue, lightness, 0.55));
  cv::Mat bgr;
  cv::cvtColor(hls, bgr, cv::COLOR_HLS2BGR);
  const cv::Vec3f f = bgr.at<cv::Vec3f>(0, 0);
  return {cv::saturate_cast<uchar>(f[0] * 255), cv::saturate_cast<uchar>(f[1] * 255),
          cv::saturate_cast<uchar>(f[2] * 255)};
}

std::string regions_caption(const qn::Arrangement& a, std::size_t inside) {
  return fmt::format("{} landmarks, {} LPB lines, {} orientation regions; {} crossings ({} in view)", a.ids().size(),
                     a.lines().size(), a.region_count(), a.crossings().size(), inside);
}

void write_regions_png(const sim::World& world, const qn::Arrangement& a, const std::string& path) {
  const RegionsCanvas c = regions_canvas(world);
  cv::Mat image(c.height + c.footer, c.width, CV_8UC3, cv::Scalar(255, 255, 255));
  {
    // Each pixel coloured by its region: the sign vector hashed as the lines are crossed.
    ProgressBar bar("neopipe qualnav regions --plot", c.height, true);
    const std::span<const qn::LpbLine> lines = a.lines();
    std::unordered_map<std::uint64_t, cv::Vec3b> colours;
    for (int y = 0; y < c.height; ++y) {
      for (int x = 0; x < c.width; ++x) {
        const Eigen::Vector2d p = c.world_at(x + 0.5, y + 0.5);
        std::uint64_t hash = 1469598103934665603ULL;
        for (const qn::LpbLine& line : lines) {
          hash = (hash ^ static_cast<std::uint64_t>(qn::orientation_from_positions(line.from, line.to, p) + 2)) *
                 1099511628211ULL;
        }
        auto [it, fresh] = colours.try_emplace(hash);
        if (fresh) it->second = region_colour(hash);
        image.at<cv::Vec3b>(y, x) = it->second;
      }
      bar.update(y + 1, "rows");
    }
  }
  const auto pt = [&](const Eigen::Vector2d& p) {
    const cv::Point2d q = c.px(p);
    return cv::Point(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
  };
  for (const qn::LpbLine& line : a.lines()) {
    const auto [from, to] = regions_line_ends(line, world);
    cv::line(image, pt(from), pt(to), cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
  }
  const cv::Rect view(0, 0, c.width, c.height);
  std::size_t inside = 0;
  for (const qn::LineCrossing& x : a.crossings()) {
    if (!view.contains(pt(x.point))) continue;
    ++inside;
    if (!x.landmark) cv::circle(image, pt(x.point), x.multiplicity() > 2 ? 4 : 2, kChartInk, cv::FILLED, cv::LINE_AA);
  }
  // Every marble of the world, the landmarks of the arrangement in red with their ids.
  for (const Eigen::Vector2d& marble : world.objects) {
    cv::circle(image, pt(marble), 3, cv::Scalar(170, 170, 170), cv::FILLED, cv::LINE_AA);
  }
  for (std::size_t k = 0; k < a.ids().size(); ++k) {
    const cv::Point at = pt(a.positions()[k]);
    cv::circle(image, at, 6, cv::Scalar(40, 39, 214), cv::FILLED, cv::LINE_AA);
    cv::putText(image, std::to_string(a.ids()[k]), at + cv::Point(7, -7), cv::FONT_HERSHEY_SIMPLEX, 0.5, kChartInk, 1,
                cv::LINE_AA);
  }
  cv::rectangle(image, pt({0, world.size.y()}), pt({world.size.x(), 0}), kChartGrid, 1);
  // The lines ran on below the picture: the footer is for the caption only.
  cv::rectangle(image, cv::Rect(0, c.height, c.width, c.footer), cv::Scalar(255, 255, 255), cv::FILLED);
  cv::putText(image, regions_caption(a, inside), {static_cast<int>(c.pad), c.height + 25}, cv::FONT_HERSHEY_SIMPLEX,
              0.5, kChartInk, 1, cv::LINE_AA);
  cv::putText(image, "red: landmarks (ids); grey lines: LPBs; black dots: crossings away from landmarks (large: m > 2)",
              {static_cast<int>(c.pad), c.height + 48}, cv::FONT_HERSHEY_SIMPLEX, 0.42, kChartInk, 1, cv::LINE_AA);
  if (!pipeline::media::write_image(path, image))
    throw std::runtime_error(fmt::format("{}: cannot write the plot", path));
}

void write_regions_svg(const sim::World& world, const qn::Arrangement& a, const std::string& path) {
  const RegionsCanvas c = regions_canvas(world);
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g clip-path=\"url(#view)\">\n"
      "<clipPath id=\"view\"><rect width=\"{0}\" height=\"{2}\"/></clipPath>\n",
      c.width, c.height + c.footer, c.height);
  for (const qn::LpbLine& line : a.lines()) {
    const auto [from, to] = regions_line_ends(line, world);
    const cv::Point2d p = c.px(from);
    const cv::Point2d q = c.px(to);
    out += fmt::format(
        "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#5a5a5a\" stroke-width=\"1\"/>\n", p.x,
        p.y, q.x, q.y);
  }
  std::size_t inside = 0;
  for (const qn::LineCrossing& x : a.crossings()) {
    const cv::Point2d p = c.px(x.point);
    if (p.x < 0 || p.y < 0 || p.x > c.width || p.y > c.height) continue;
    ++inside;
    if (!x.landmark) {
      out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"black\"/>\n", p.x, p.y,
                         x.multiplicity() > 2 ? 4 : 2);
    }
  }
  out += "</g>\n";
  for (const Eigen::Vector2d& m : world.objects) {
    const cv::Point2d p = c.px(m);
    out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"#aaaaaa\"/>\n", p.x, p.y);
  }
  for (std::size_t k = 0; k < a.ids().size(); ++k) {
    const cv::Point2d p = c.px(a.positions()[k]);
    out += fmt::format(
        "<circle cx=\"{0:.2f}\" cy=\"{1:.2f}\" r=\"6\" fill=\"#d62728\"/>\n<text x=\"{2:.2f}\" y=\"{3:.2f}\" "
        "font-family=\"sans-serif\" font-size=\"13\">{4}</text>\n",
        p.x, p.y, p.x + 7, p.y - 7, a.ids()[k]);
  }
  out += fmt::format("<text x=\"{:.0f}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"14\">{}</text>\n</svg>\n",
                     c.pad, c.height + 25, regions_caption(a, inside));
  std::ofstream file(path, std::ios::trunc);
  file << out;
  if (!file) throw std::runtime_error(fmt::format("{}: cannot write the plot", path));
}

int qualnav_regions_command(const QualnavArgs& a) {
  if (!a.plot.empty() && !a.plot.ends_with(".png") && !a.plot.ends_with(".svg")) {
    throw UsageError{fmt::format("--plot {}: the picture must be a .png or .svg file", a.plot)};
  }
  const sim::World world = sim::load_world(a.world);
  const std::vector<qn::LandmarkId> ids = qualnav_landmark_ids(a, world);
  if (ids.size() > kMaxRegionLandmarks) {
    // n landmarks and 3·C(n,4) other crossings in general position.
    const auto n = static_cast<double>(ids.size());
    throw std::runtime_error(
        fmt::format("{}: {} landmarks would give about {:.0f} crossings; choose at most {} with "
                    "--landmarks",
                    a.world, ids.size(), n + n * (n - 1) * (n - 2) * (n - 3) / 8, kMaxRegionLandmarks));
  }
  std::vector<Eigen::Vector2d> positions;
  positions.reserve(ids.size());
  for (const qn::LandmarkId id : ids) positions.push_back(world.objects[id]);
  std::optional<qn::Arrangement> arrangement;
  try {
    arrangement.emplace(ids, positions);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(a.world + ": " + e.what());
  }
  const qn::Arrangement& arr = *arrangement;
  if (!a.plot.empty()) {
    if (a.plot.ends_with(".svg")) {
      write_regions_svg(world, arr, a.plot);
    } else {
      write_regions_png(world, arr, a.plot);
    }
  }
  if (a.json) {
    // Streamed a crossing at a time: sixty landmarks have 1.5 million, too many for one JSON tree.
    std::string out = fmt::format(R"({{"landmarks":{},"ids":{},"lines":{},"regions":{},"crossings":[)", ids.size(),
                                  json(ids).dump(), arr.lines().size(), arr.region_count());
    bool first = true;
    for (const qn::LineCrossing& c : arr.crossings()) {
      out += (first ? "" : ",") + qualnav_crossing_json(arr, c).dump();
      first = false;
      if (out.size() > (1U << 20U)) {
        std::cout << out;
        out.clear();
      }
    }
    std::cout << out << "]}\n";
    return kExitOk;
  }
  std::size_t beyond_landmarks = 0;
  for (const qn::LineCrossing& c : arr.crossings()) beyond_landmarks += c.landmark ? 0 : 1;
  std::string text = fmt::format(
      "{}: {} landmarks, {} LPB lines, {} orientation regions (1 + N + sum(m_p - 1)); {} crossings, {} away from the "
      "landmarks\n{:>12} {:>12} {:>3}  lines (landmark pairs)\n",
      a.world, ids.size(), arr.lines().size(), arr.region_count(), arr.crossings().size(), beyond_landmarks, "x", "y",
      "m");
  for (const qn::LineCrossing& c : arr.crossings()) {
    std::string lines;
    for (const std::size_t i : c.lines) {
      lines += fmt::format("{}({},{})", lines.empty() ? "" : " ", arr.pairs()[i].first, arr.pairs()[i].second);
    }
    text += fmt::format("{:>12.3f} {:>12.3f} {:>3}  {}{}\n", c.point.x(), c.point.y(), c.multiplicity(), lines,
                        c.landmark ? fmt::format("  (landmark {})", *c.landmark) : "");
  }
  std::cout << text;
  return kExitOk;
}

int qualnav_productions_command(const QualnavArgs& a) {
  const std::vector<qn::ProductionCell> cells = qn::production_table();
  if (a.json) {
    json orders = json::array();
    for (const std::string_view o : qn::production_orders()) orders.push_back(std::string(o));
    json list = json::array();
    for (const qn::ProductionCell& c : cells) {
      list.push_back({{"x", std::string{qn::specifier_letter(c.x)}},
                      {"y", std::string{qn::specifier_letter(c.y)}},
                      {"order", c.order},
                      {"production", c.production}});
    }
    std::cout << json{{"orders", orders}, {"cells", list}}.dump() << '\n';
    return kExitOk;
  }
  // The spec's layout: a row per (x, y), a column per left-to-right order.
  std::string text = "Heading productions of x[A B] and y[C D] (spec qualnav.md §5); columns: left-to-right order\n";
  text += fmt::format("{:<4} {:<4}", "A,B", "C,D");
  for (const std::string_view o : qn::production_orders()) text += fmt::format(" {:<6}", o);
  text += '\n';
  const std::size_t columns = qn::production_orders().size();
  for (std::size_t row = 0; row * columns < cells.size(); ++row) {
    const qn::ProductionCell& first = cells[row * columns];
    text += fmt::format("{:<4} {:<4}", qn::specifier_letter(first.x), qn::specifier_letter(first.y));
    for (std::size_t k = 0; k < columns; ++k) {
      const std::string& p = cells[row * columns + k].production;
      // "–" is one column wide but three bytes: pad by what shows.
      text += " " + p + std::string(p == qn::kNoProduction ? 5 : 6 - std::min<std::size_t>(6, p.size()), ' ');
    }
    text += '\n';
  }
  std::cout << text;
  return kExitOk;
}

}  // namespace

CLI::App* add_qualnav_command(CLI::App& app, QualnavArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "qualnav", "Qualnav's topological tools (spec qualnav.md): orientation regions of a world, heading productions");
  cmd->require_subcommand(1);
  CLI::App* regions = cmd->add_subcommand(
      "regions",
      "The orientation regions of a world's marbles: the arrangement of their LPB lines, its crossings with their "
      "multiplicity m_p and the region count R = 1 + N + sum(m_p - 1)");
  regions->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  regions
      ->add_option("--landmarks", a.landmarks,
                   fmt::format("Comma-separated marble ids (default: every marble; at most {})", kMaxRegionLandmarks))
      ->type_name("I,J,...");
  regions->add_flag("--json", a.json,
                    R"(One JSON object: {"landmarks": n, "ids": [...], "lines": N, "regions": R, "crossings": )"
                    R"([{"x", "y", "multiplicity", "landmark" (id or null), "lines": [[i, j], ...]}]})");
  regions->add_option("--plot", a.plot,
                      "Draw the arrangement over the workspace, each region in its own colour, to a .png (or the "
                      "lines alone to an .svg)");
  CLI::App* productions = cmd->add_subcommand(
      "productions", "The table of heading productions of spec §5: x[A B] and y[C D] in each left-to-right order");
  productions->add_flag("--json", a.json,
                        R"(One JSON object: {"orders": ["ABCD", ...], "cells": [{"x": "r", "y": "r", "order": )"
                        R"("ABCD", "production": "r[CD]"}, ...]} (96 cells; "–" for none))");
  return cmd;
}

int qualnav_command(const CLI::App& qualnav, const QualnavArgs& args) {
  if (qualnav.got_subcommand("regions")) return qualnav_regions_command(args);
  return qualnav_productions_command(args);
}

}  // namespace neopipe::apps
