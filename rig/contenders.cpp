#include "rig/contenders.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "nav/mapmaker/map_maker.hpp"
#include "rig/experiment.hpp"
#include "rig/nx_system.hpp"
#include "rig/qrm_system.hpp"
#include "rig/qualnav_system.hpp"

namespace neopipe::rig {
namespace {

Contender park_kender_contender(const NavSetup& setup, const NavRequest& request) {
  const auto criterion = nav::mapmaker::parse_criterion(request.cost);
  if (!criterion) throw RequestError(fmt::format("--cost {}: unknown criterion", request.cost));
  const std::string survey = request.sigma_map
                                 ? fmt::format("a survey of every object (Gaussian sd {} mm)", *request.sigma_map)
                                 : std::string("a survey of every object by the calibrated global camera");
  return {make_park_kender(setup.survey, setup.settings, *criterion), survey};
}

Contender qrm_contender(const sim::World& world, const ContendersRequest& request) {
  if (world.objects.size() < 3) {
    throw RequestError(
        fmt::format("qrm needs at least three marbles; {} has {}", request.nav.world, world.objects.size()));
  }
  QrmSettings settings;
  settings.images = request.qrm_images;
  settings.seed = request.nav.seed;
  settings.bearing_noise_deg = request.bearing_noise_deg;
  settings.navigator.marble_radius_mm = world.marble_diameter / 2;
  settings.navigator.observation.nearest = request.qrm_k;
  const auto total = static_cast<std::int64_t>(request.qrm_images);
  nav::qrm::RelationalMap map = build_map_by_tour(world, settings, nullptr, [&](std::size_t done) {
    if (request.progress) request.progress("qrm: imaging tour", static_cast<std::int64_t>(done), total);
  });
  return {std::make_unique<QrmSystem>(world, std::move(map), settings),
          fmt::format("a relational map from a tour of {} panoramas", request.qrm_images)};
}

Contender qualnav_contender(const sim::World& world, const ContendersRequest& request) {
  QualnavSettings settings;
  settings.seed = request.nav.seed;
  settings.sensing.range_error = request.qualnav_range_error;
  settings.sensing.bearing_noise_deg = request.bearing_noise_deg;
  return {std::make_unique<QualnavSystem>(world, settings),
          "a visual memory: viewframes every 20 mm along the journey's route, taught once"};
}

Contender nx_contender(const sim::World& world, const ContendersRequest& request) {
  if (world.objects.size() < 3) {
    throw RequestError(
        fmt::format("nx needs at least three marbles; {} has {}", request.nav.world, world.objects.size()));
  }
  NxSettings settings;
  settings.seed = request.nav.seed;
  settings.range_error = request.nx_range_error;
  settings.arm = {request.nav.sigma_move, request.nav.sigma_rot};
  settings.explore.max_places = request.nx_places;
  const auto total = static_cast<std::int64_t>(request.nx_places);
  NxExploration exploration = explore_world(world, settings, [&](std::size_t done) {
    if (request.progress) request.progress("nx: exploring, places", static_cast<std::int64_t>(done), total);
  });
  return {std::make_unique<NxSystem>(world, std::move(exploration), settings),
          fmt::format("nothing: it explores first ({} places)", request.nx_places)};
}

}  // namespace

std::vector<std::string> contender_names() {
  return {"park-kender", "qrm", "qualnav", "nx"};
}

ContenderSet make_contenders(const ContendersRequest& request) {
  const std::vector<std::string> known = contender_names();
  const std::vector<std::string> names = request.systems.empty() ? known : request.systems;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (std::find(known.begin(), known.end(), names[i]) == known.end()) {
      throw RequestError(fmt::format("--systems: unknown system '{}' (known: {})", names[i], fmt::join(known, ", ")));
    }
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
        names.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw RequestError(fmt::format("--systems: '{}' is named twice", names[i]));
    }
  }
  if (request.qrm_images < 1) throw RequestError("--images: QRM's tour needs at least one image");
  if (request.qrm_k < 3) throw RequestError(fmt::format("--k {}: a triple needs at least 3 landmarks", request.qrm_k));
  if (!(request.bearing_noise_deg >= 0) || !std::isfinite(request.bearing_noise_deg)) {
    throw RequestError(fmt::format("--bearing-noise {}: must be finite and not negative", request.bearing_noise_deg));
  }
  if (!(request.qualnav_range_error >= 0) || !std::isfinite(request.qualnav_range_error)) {
    throw RequestError(
        fmt::format("--qualnav-range-error {}: must be finite and not negative", request.qualnav_range_error));
  }
  if (!(request.nx_range_error >= 0 && request.nx_range_error < 1)) {
    throw RequestError(fmt::format("--nx-range-error {}: must lie in [0, 1)", request.nx_range_error));
  }
  if (request.nx_places < 1) throw RequestError("--places: NX's exploration needs at least one place");
  ContenderSet set;
  set.setup = std::make_unique<NavSetup>(nav_setup(request.nav));
  for (const std::string& name : names) {
    if (name == "park-kender") set.contenders.push_back(park_kender_contender(*set.setup, request.nav));
    if (name == "qrm") set.contenders.push_back(qrm_contender(set.setup->world, request));
    if (name == "qualnav") set.contenders.push_back(qualnav_contender(set.setup->world, request));
    if (name == "nx") set.contenders.push_back(nx_contender(set.setup->world, request));
  }
  return set;
}

}  // namespace neopipe::rig
