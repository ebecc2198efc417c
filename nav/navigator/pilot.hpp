#pragma once
// Internal to the navigator library: the state of one journey (the eye, the arm, what was seen
// last, the report being written) and the custom-map steps built on it. Everything here works in
// window coordinates (mm from the window's south-west corner); moving the tool by d moves the window
// by d, so an object seen at p is expected at p - d after the move.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/navigator/navigator.hpp"

namespace neopipe::nav::navigator::detail {

class Pilot {
 public:
  Pilot(Eye& eye, Arm& arm, const NavigatorConfig& config, Observer* observer, JourneyReport& report)
      : eye_(eye), arm_(arm), config_(config), observer_(observer), report_(report) {}

  const NavigatorConfig& config() const { return config_; }
  const WindowModel& window() const { return config_.window; }
  Observer* observer() const { return observer_; }
  JourneyReport& report() { return report_; }

  /// Grabs and processes a frame; the sighting stays current until the next look.
  const Sighting& look();
  const Sighting& sighting() const { return sighting_; }
  /// Commands a move of the window by `d` (tool frame, no turn) and looks again.
  const Sighting& move_and_look(const Eigen::Vector2d& d);

 private:
  Eye& eye_;
  Arm& arm_;
  const NavigatorConfig& config_;
  Observer* observer_;
  JourneyReport& report_;
  Sighting sighting_;
};

/// A failure the navigator is aware of; follow() turns it into the report's ending and reason.
struct Failure {
  Ending ending = Ending::lost;
  std::string reason;
};

/// Index of the object of `sighting` nearest `predicted`, if one lies within `gate` mm.
std::optional<std::size_t> nearest(const Sighting& sighting, const Eigen::Vector2d& predicted, double gate);

/// How far an object seen before a move of length `moved` may appear from its predicted place.
double tracking_gate(double moved);

/// Visual servoing: brings the landmark now seen at `landmark` to `corner`. Returns where it is
/// held (within the adjust tolerance), or a Failure when it is lost from sight or does not settle.
std::optional<Failure> adjust(Pilot& pilot, Eigen::Vector2d& landmark, Corner corner);

/// The landmark `description` selects in the current view, the object seen at `reference` being
/// the reference. Its position, or a Failure.
std::optional<Failure> seek(Pilot& pilot, const Eigen::Vector2d& reference, Description description,
                            Eigen::Vector2d& landmark);

/// Slides the window along reference -> landmark (positive) or back until an object that was not in
/// view enters; `found` is where that new object is seen. Failure after config.max_slide.
std::optional<Failure> slide(Pilot& pilot, const Eigen::Vector2d& reference, const Eigen::Vector2d& via,
                             Direction direction, Eigen::Vector2d& found);

/// Looks around the landmark at `landmark` (holds it at each corner in turn) and counts the occupied
/// quadrants. The landmark ends held at the last corner visited; `landmark` is updated.
std::optional<Failure> measure_qoc(Pilot& pilot, Eigen::Vector2d& landmark, int& qoc);

/// Verification and recovery of one entry (park-kender.md §7): measures the landmark's QOC and
/// follows the entry's rules until the QOC is the verified one. Updates `landmark` to the object
/// finally taken, and `record`.
std::optional<Failure> verify(Pilot& pilot, const MapEntry& entry, Eigen::Vector2d& landmark, EntryRecord& record);

}  // namespace neopipe::nav::navigator::detail
