#pragma once
// The navigation experiment harness: the simulated world on one side, the navigator on the other,
// and the ground truth kept where the navigator cannot see it. Adapts sim::SimulatedArm to
// navigator::Arm and the onboard camera to the navigator's frame source, places the arm at the
// route's start, runs navigator::follow, and judges the journey against the truth (nav_outcome.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "apps/nav_outcome.hpp"
#include "nav/mapmaker/map_maker.hpp"
#include "nav/navigator/navigator.hpp"
#include "sim/arm/motion_model.hpp"
#include "sim/arm/scara.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {

/// The experiment's error settings, as the command line gives them.
struct ExperimentErrors {
  double sigma_move = 0.003;  ///< sd of the arm's translation (along and across) per mm moved
  double sigma_rot = 0.002;   ///< sd of the arm's heading, degrees per mm moved
};

/// The arm's motion errors for these settings. With both per-mm terms 0 the arm is exact (no
/// repeatability floor either), so that error-free runs can be asked for.
sim::MotionErrors motion_errors(const ExperimentErrors& errors);

/// Independent random streams from one seed: changing how many numbers one consumer draws (the
/// arm's normals, say) must not shift another's (the camera noise).
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream);

/// A SCARA arm that can hold a window anywhere over the world and one window beyond its edges, so
/// a trajectory may slide off the world without hitting the arm's reach first.
sim::ScaraGeometry arm_for_world(const sim::World& world, double window_side);

/// Whether the landmark the navigator held at one entry was the one the map-maker meant.
struct HeldLandmark {
  std::size_t entry = 0;
  std::uint32_t intended = 0;  ///< the route's object for this entry
  std::uint32_t actual = 0;    ///< the world object nearest to where the navigator held it
  double offset = 0;           ///< mm between that object and the held position
  bool correct = false;
  Eigen::Vector2d tool{0, 0};  ///< where the window's centre really was, mm
};

struct JourneyResult {
  nav::navigator::JourneyReport report;
  Outcome outcome = Outcome::fail_lost;
  std::vector<HeldLandmark> held;
  std::int64_t frames = 0;
  double commanded_travel = 0;         ///< mm, what the navigator asked for
  double true_travel = 0;              ///< mm, what the tool really moved
  int refused_moves = 0;               ///< commands the arm could not reach (it stayed where it was)
  std::vector<Eigen::Vector2d> track;  ///< the window's true centre (the tool) after each move, start first
};

struct JourneySettings {
  ExperimentErrors errors;
  nav::navigator::NavigatorConfig navigator;  ///< window, tolerances, recovery on/off
  std::uint64_t seed = 1;                     ///< arm errors and camera noise of this journey
};

/// Runs one journey along `route` (planned by a map-maker over `world`'s objects). `observer`, if
/// given, also sees every landmark and frame (videos). Never throws for navigation failures.
JourneyResult run_journey(const sim::World& world, const nav::mapmaker::Route& route, const JourneySettings& settings,
                          nav::navigator::Observer* observer = nullptr);

}  // namespace neopipe::apps
