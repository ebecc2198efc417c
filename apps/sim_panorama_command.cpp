#include "apps/sim_panorama_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "apps/cli_support.hpp"
#include "nav/common/panorama_reading.hpp"
#include "pipeline/media/media.hpp"
#include "sim/panorama.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

constexpr double kPanoramaDegree = std::numbers::pi / 180;

sim::Pose2 parse_at(const std::string& text) {
  const UsageError bad{"--at '" + text + "': expected X,Y or X,Y,HEADING (mm, mm, degrees)"};
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      throw bad;
    }
    if (used != item.size() || !std::isfinite(x)) throw bad;
    v.push_back(x);
  }
  if (v.size() != 2 && v.size() != 3) throw bad;
  return {v[0], v[1], v.size() == 3 ? v[2] * kPanoramaDegree : 0.0};
}

// Each identity its own hue (golden-ratio steps, so neighbours in id differ), full value on black.
cv::Mat false_colour(const cv::Mat& ring) {
  cv::Mat hsv(ring.size(), CV_8UC3, cv::Scalar::all(0));
  for (int v = 0; v < ring.rows; ++v) {
    const auto* in = ring.ptr<std::int16_t>(v);
    auto* out = hsv.ptr<cv::Vec3b>(v);
    for (int u = 0; u < ring.cols; ++u) {
      if (in[u] == 0) continue;
      const double step = std::fmod(in[u] * 0.618033988749895, 1.0);
      out[u] = cv::Vec3b(static_cast<std::uint8_t>(180 * step), static_cast<std::uint8_t>(150 + in[u] % 4 * 35), 255);
    }
  }
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr;
}

}  // namespace

void add_sim_panorama_options(CLI::App& cmd, SimPanoramaArgs& a) {
  cmd.add_option("--world", a.world, "World file (YAML), e.g. from neopipe sim world")->required()->type_name("W.yaml");
  cmd.add_option("--at", a.at,
                 "Where the tool (the robot) stands: x,y in mm on the table, and its heading in degrees "
                 "counter-clockwise from the table's +x axis (default 0)")
      ->required()
      ->type_name("X,Y[,HEADING]");
  cmd.add_option("--out", a.out, "False-colour picture of the ring (3600 x 320, a hue per marble id, black background)")
      ->type_name("ring.png");
  cmd.add_flag("--json", a.json,
               "Print the readings as JSON: {\"readings\": [{\"id\", \"bearing_deg\", \"range_mm\": [lo, hi], "
               "\"area_px\", \"partial\"}, ...], \"compass\": {\"heading_deg\", \"sigma_deg\"}}");
  cmd.add_option("--noise", a.noise, "Bearing noise: sd of each disc's Gaussian jitter, degrees")
      ->check(CLI::Range(0.0, 90.0))
      ->capture_default_str();
  cmd.add_option("--range", a.range, "R_s: marbles whose centre lies farther are not seen, mm")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  cmd.add_option("--seed", a.seed, "Seed of the bearing noise and of the compass")->capture_default_str();
  cmd.footer(
      "Column u of the ring looks at bearing (u + 1/2) x 0.1 deg, counter-clockwise from the tool's +x axis; each "
      "marble within R_s is a disc of angular radius asin(r/d) on row 160, value id + 1, nearer ones in front.\n"
      "Without --json the readings are printed as CSV: id,bearing_deg,range_lo_mm,range_hi_mm,area_px,partial.");
}

int sim_panorama_command(const SimPanoramaArgs& a) {
  const sim::World world = sim::load_world(a.world);
  const sim::Pose2 tool = parse_at(a.at);
  if (!(tool.x >= 0 && tool.y >= 0 && tool.x <= world.size.x() && tool.y <= world.size.y())) {
    throw std::runtime_error(fmt::format("--at {}: ({}, {}) is outside the {} x {} mm table", a.at, tool.x, tool.y,
                                         world.size.x(), world.size.y()));
  }
  const auto nearest = sim::nearest_surface(world, {tool.x, tool.y});
  if (nearest && nearest->gap_mm < 0) {
    throw std::runtime_error(
        fmt::format("--at {}: inside marble {} (centre {}, {}): the sensor sees nothing from there", a.at, nearest->id,
                    world.objects[nearest->id].x(), world.objects[nearest->id].y()));
  }
  if (nearest && nearest->gap_mm < sim::kMinClearanceMm) {
    std::cerr << fmt::format(
        "neopipe sim panorama: warning: {:.2f} mm from marble {}'s surface; the robot keeps {} mm from marbles\n",
        nearest->gap_mm, nearest->id, sim::kMinClearanceMm);
  }
  sim::PanoramaSettings settings;
  settings.bearing_noise_deg = a.noise;
  settings.range_mm = a.range;
  settings.seed = a.seed;
  sim::PanoramicSensor sensor(world, settings);
  const sim::Ring ring = sensor.ring(tool);
  const double compass = sensor.compass_deg(tool);
  nav::PanoramaReader reader({world.marble_diameter / 2, a.noise});
  const auto readings = reader.read(ring.image);

  if (!a.out.empty() && !pipeline::media::write_image(a.out, false_colour(ring.image))) {
    throw std::runtime_error(a.out + ": cannot write an image there (use .png, .jpg, .tif or .bmp)");
  }
  if (a.json) {
    nlohmann::ordered_json j;
    j["pose"] = {{"x", tool.x}, {"y", tool.y}, {"heading_deg", tool.theta / kPanoramaDegree}};
    j["readings"] = nlohmann::ordered_json::array();
    for (const auto& r : readings) {
      j["readings"].push_back({{"id", r.id},
                               {"bearing_deg", r.bearing_deg},
                               {"range_mm", {r.range_lo_mm, r.range_hi_mm}},
                               {"area_px", r.area_px},
                               {"partial", r.partial}});
    }
    j["compass"] = {{"heading_deg", compass}, {"sigma_deg", settings.compass_sigma_deg}};
    std::cout << j.dump() << "\n";
  } else {
    std::cout << "id,bearing_deg,range_lo_mm,range_hi_mm,area_px,partial\n";
    for (const auto& r : readings) {
      std::cout << fmt::format("{},{:.4f},{:.3f},{:.3f},{},{}\n", r.id, r.bearing_deg, r.range_lo_mm, r.range_hi_mm,
                               r.area_px, r.partial ? 1 : 0);
    }
  }
  std::cerr << fmt::format("neopipe sim panorama: {} of {} marbles within {} mm, {} seen; compass {:.2f} deg{}\n",
                           ring.discs, world.objects.size(), a.range, readings.size(), compass,
                           a.out.empty() ? "" : " -> " + a.out);
  return kExitOk;
}

}  // namespace neopipe::apps
