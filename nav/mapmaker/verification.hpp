#pragma once
// Error detection and recovery by Quadrant Occupancy Count (park-kender.md §7, paper §6.3): after
// each step the navigator looks around the landmark it reached; if its QOC is not the intended
// landmark's, it knows it went wrong, and a fixed table "if QOC = k then (corner, description)"
// carried in the custom map leads it back.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/mapmaker/reliability.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

enum class Verifiability : std::uint8_t {
  trivial,          ///< nothing else could have been taken: verification implicit (paper: TRIVIAL CASE)
  correctable,      ///< detectable, and the rules lead every mistake back (CORRECTABLE)
  not_correctable,  ///< detectable, but some mistake cannot be led back: an aware failure
  unverifiable,     ///< a mistake could look the same: not detectable (UNVERIFIABLE)
};

std::string_view verifiability_name(Verifiability v);

struct StepCheck {
  Verifiability kind = Verifiability::trivial;
  int qoc = 0;                            ///< the intended landmark's QOC
  std::vector<std::uint32_t> confusable;  ///< what the navigator could take instead, ascending
  std::vector<RecoveryRule> rules;        ///< the entry's E: recovery rules, then (qoc, -)
};

/// Objects the navigator could mistake for `landmark` when seeking at `from`: the others in view
/// (not the reference). Empty for an Obvious description: it fails aware rather than picks wrong.
std::vector<std::uint32_t> confusable_in_view(const WorldViews& views, const Placement& from, std::uint32_t landmark,
                                              Description description);

/// Objects that could enter the sliding window first instead of the trajectory's goal: the first
/// to enter over directions within +-3 sd of the direction error (static: sqrt(2) sigma / baseline;
/// dynamic: heading and across-track errors over the slide), sampled at 61 directions, plus the
/// objects confusable with the landmark that defines the direction.
std::vector<std::uint32_t> confusable_on_trajectory(const WorldViews& views, const Trajectory& trajectory,
                                                    const NavigatorErrors& errors);

/// Whether reaching `landmark` can be verified, and the recovery rules: for each QOC value among the
/// confusable objects, a (corner, Isol) that takes every object with that QOC to the landmark,
/// directly or through other rules (paper §6.3.2, conditions 1-3). With a `tolerance` (mm) every
/// object may show any QOC of its views.qoc_range: a step is detectable only when no mistake's range
/// meets the landmark's, and the rules must cover every QOC a mistake may show. So no rule ever names
/// a QOC the landmark itself may show when an object lies that close to one of its quadrants' borders.
StepCheck check_step(const WorldViews& views, std::uint32_t landmark, std::span<const std::uint32_t> confusable,
                     double tolerance = 0);

/// What the map's table prints for a step: "VERIFY QOC -> 2 (CORRECTABLE)" and its rules.
std::string verification_line(const StepCheck& check);

}  // namespace neopipe::nav::mapmaker
