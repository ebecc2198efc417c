#pragma once
// The imaging tour of QRM map building (spec qrm.md §6, §9, §10): the tool stops at imaging
// positions, the panoramic sensor (qualnav.md §2) renders its ring there with a random zero
// direction (no compass), the engine's panorama graph reads it, and the k nearest sightings are
// fused into a RelationalMap (nav::qrm::observe). The rig sees the world to render the ring and to
// choose positions; the map only ever receives bearings, range estimates and identities.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "nav/common/panorama_reading.hpp"
#include "nav/qrm/observation.hpp"
#include "nav/qrm/relational_map.hpp"
#include "sim/panorama.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

struct QrmImagingSettings {
  /// The sensor: range R_s, the bearing noise (degrees) and its seed. The compass is not used.
  sim::PanoramaSettings sensor;
  /// k (the nearest landmarks used per image) and the measurement's rho, tau, depth.
  nav::qrm::ObservationOptions observation;
  /// Seeds the sensor's zero direction at each image (uniform in [0, 2 pi), spec §9: no compass).
  std::uint64_t heading_seed = 1;
  /// Sightings the reader flags `partial` (a disc partly hidden by a nearer one) have a range
  /// estimate too large by an unknown factor, which can invert the range order the measurement
  /// trusts; by default they are left out of the image (a hidden marble is seen from elsewhere).
  bool use_partial_sightings = false;
};

/// What one image did.
struct QrmImageReport {
  Eigen::Vector2d position{0, 0};     ///< tool, mm (world frame)
  double heading = 0;                 ///< the sensor's zero direction, rad from the world's +x (truth)
  std::size_t sightings = 0;          ///< identities the reader found in the ring
  std::size_t partial = 0;            ///< of them, flagged partial (left out unless asked)
  nav::qrm::ObservationReport fused;  ///< landmarks used (<= k), triples, refined, inconsistent
  double read_seconds = 0;            ///< rendering and reading the ring
  double fuse_seconds = 0;            ///< measuring and fusing its triples
};

/// The sensor at a sequence of imaging positions over one world, fusing into a map the caller owns.
/// Deterministic for given settings and positions.
class QrmImaging {
 public:
  /// Keeps a copy of the world. Throws std::invalid_argument as sim::render_ring does.
  QrmImaging(const sim::World& world, const QrmImagingSettings& settings);
  ~QrmImaging();
  QrmImaging(const QrmImaging&) = delete;
  QrmImaging& operator=(const QrmImaging&) = delete;

  /// The sightings of one ring taken at `position` with zero direction `heading` (rad), as the map
  /// receives them (bearing in radians in the sensor frame, range = the reader's estimate, mm),
  /// partial ones dropped unless the settings ask for them. Draws the sensor's bearing noise.
  std::vector<nav::qrm::LandmarkSighting> sightings(const Eigen::Vector2d& position, double heading,
                                                    std::size_t* found = nullptr, std::size_t* partial = nullptr);

  /// One image at `position` (zero direction drawn from the heading stream) fused into `map`.
  QrmImageReport image(nav::qrm::RelationalMap& map, const Eigen::Vector2d& position);

  [[nodiscard]] const QrmImagingSettings& settings() const { return settings_; }

 private:
  sim::World world_;
  QrmImagingSettings settings_;
  sim::Random headings_;
  sim::Random bearing_noise_;
  std::unique_ptr<nav::PanoramaReader> reader_;
};

/// Called after each image with its index (0-based) and report.
using QrmImageCallback = std::function<void(std::size_t, const QrmImageReport&)>;

/// One image at each position in turn, fused into `map`; the reports in order.
std::vector<QrmImageReport> qrm_imaging_tour(const sim::World& world, std::span<const Eigen::Vector2d> positions,
                                             const QrmImagingSettings& settings, nav::qrm::RelationalMap& map,
                                             const QrmImageCallback& on_image = {});

/// `count` positions drawn uniformly in the workspace, each redrawn until the tool keeps at least
/// `min_gap_mm` from every marble's surface. Same arguments -> same positions. Throws
/// std::invalid_argument when no clear position turns up in 10,000 draws.
std::vector<Eigen::Vector2d> random_imaging_positions(const sim::World& world, std::size_t count, std::uint64_t seed,
                                                      double min_gap_mm = sim::kMinClearanceMm);

}  // namespace neopipe::rig
