#pragma once
// The navigation systems a comparison can run, made by name over one world with the settings a
// user states once: Park & Kender's on the survey (rig/reports.hpp nav_setup), QRM on the map of its
// imaging tour, Qualnav on the viewpaths of each journey's taught route, NX on what it explored. Each comes with what
// it had to know before its first journey.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rig/comparison.hpp"
#include "rig/reports.hpp"

namespace neopipe::rig {

/// The systems make_contenders knows, in the order a comparison runs them by default.
std::vector<std::string> contender_names();

struct ContendersRequest {
  /// The world, Park & Kender's survey and options, the arm's errors, the seed, the threads: the
  /// settings `neopipe nav` takes, shared by every system.
  NavRequest nav;
  std::vector<std::string> systems;  ///< names of contender_names(); empty: all of them
  std::size_t qrm_images = 30;       ///< QRM: imaging positions of the tour that builds its map
  std::size_t qrm_k = 18;            ///< QRM: landmarks of an image fused
  double bearing_noise_deg = 0;      ///< the panoramic sensor's bearing noise (QRM, Qualnav)
  double qualnav_range_error = 0.5;  ///< Qualnav: the range estimates' error e (the papers' 50 %)
  double nx_range_error = 0.1;       ///< NX: the range ring's relative error bound
  std::size_t nx_places = 40;        ///< NX: the exploration's budget of places
  /// Told as each system's preparation advances: a stage ("qrm: imaging tour"), done and total.
  std::function<void(const std::string& stage, std::int64_t done, std::int64_t total)> progress;
};

/// The world and the systems made over it (they refer to the world: keep the set alive while they run).
struct ContenderSet {
  std::unique_ptr<NavSetup> setup;  ///< its world serves every system; its survey, Park & Kender's
  std::vector<Contender> contenders;
  [[nodiscard]] const sim::World& world() const { return setup->world; }
};

/// Throws RequestError for an unknown or repeated system name or a bad setting (naming it), and
/// what nav_setup throws for the world.
ContenderSet make_contenders(const ContendersRequest& request);

}  // namespace neopipe::rig
