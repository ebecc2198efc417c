#include "rig/qrm_imaging.hpp"

#include <chrono>
#include <numbers>
#include <stdexcept>
#include <string>

namespace neopipe::rig {
namespace {

double seconds_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// Two streams of one seed: the headings must not shift when the noise draws more or fewer numbers.
constexpr std::uint64_t kBearingNoiseOffset = 0x5DEECE66DULL;

}  // namespace

QrmImaging::QrmImaging(const sim::World& world, const QrmImagingSettings& settings)
    : world_(world),
      settings_(settings),
      headings_(settings.heading_seed),
      bearing_noise_(settings.sensor.seed + kBearingNoiseOffset),
      reader_(std::make_unique<nav::PanoramaReader>(
          nav::PanoramaModel{world.marble_diameter / 2, settings.sensor.bearing_noise_deg})) {
  if (world_.objects.size() > sim::kRingMaxMarbles) {
    throw std::invalid_argument("qrm imaging: the ring holds at most 32767 marbles");
  }
}

QrmImaging::~QrmImaging() = default;

std::vector<nav::qrm::LandmarkSighting> QrmImaging::sightings(const Eigen::Vector2d& position, double heading,
                                                              std::size_t* found, std::size_t* partial) {
  const sim::Ring ring =
      sim::render_ring(world_, sim::Pose2{position.x(), position.y(), heading}, settings_.sensor, &bearing_noise_);
  const std::vector<nav::PanoramaSighting> read = reader_->read(ring.image);
  std::vector<nav::qrm::LandmarkSighting> out;
  out.reserve(read.size());
  std::size_t flagged = 0;
  for (const nav::PanoramaSighting& s : read) {
    if (s.partial) {
      ++flagged;
      if (!settings_.use_partial_sightings) continue;
    }
    out.push_back({s.id, s.bearing_deg * std::numbers::pi / 180, s.range_mm});
  }
  if (found != nullptr) *found = read.size();
  if (partial != nullptr) *partial = flagged;
  return out;
}

QrmImageReport QrmImaging::image(nav::qrm::RelationalMap& map, const Eigen::Vector2d& position) {
  QrmImageReport report;
  report.position = position;
  report.heading = headings_.uniform(0, 2 * std::numbers::pi);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<nav::qrm::LandmarkSighting> seen =
      sightings(position, report.heading, &report.sightings, &report.partial);
  const auto read = std::chrono::steady_clock::now();
  report.fused = nav::qrm::observe(map, seen, settings_.observation);
  report.read_seconds = seconds_between(start, read);
  report.fuse_seconds = seconds_between(read, std::chrono::steady_clock::now());
  return report;
}

std::vector<QrmImageReport> qrm_imaging_tour(const sim::World& world, std::span<const Eigen::Vector2d> positions,
                                             const QrmImagingSettings& settings, nav::qrm::RelationalMap& map,
                                             const QrmImageCallback& on_image) {
  QrmImaging imaging(world, settings);
  std::vector<QrmImageReport> reports;
  reports.reserve(positions.size());
  for (const Eigen::Vector2d& p : positions) {
    reports.push_back(imaging.image(map, p));
    if (on_image) on_image(reports.size() - 1, reports.back());
  }
  return reports;
}

std::vector<Eigen::Vector2d> random_imaging_positions(const sim::World& world, std::size_t count, std::uint64_t seed,
                                                      double min_gap_mm) {
  constexpr int kMaxDraws = 10000;
  sim::Random random(seed);
  std::vector<Eigen::Vector2d> positions;
  positions.reserve(count);
  while (positions.size() < count) {
    bool placed = false;
    for (int draw = 0; draw < kMaxDraws && !placed; ++draw) {
      const Eigen::Vector2d p{random.uniform(0, world.size.x()), random.uniform(0, world.size.y())};
      if (sim::keeps_clear(world, p, min_gap_mm)) {
        positions.push_back(p);
        placed = true;
      }
    }
    if (!placed) {
      throw std::invalid_argument("qrm imaging: no position keeps " + std::to_string(min_gap_mm) +
                                  " mm from every marble in " + std::to_string(kMaxDraws) + " draws");
    }
  }
  return positions;
}

}  // namespace neopipe::rig
