// Error detection and recovery (park-kender.md §7): the landmark's quadrant occupancy count, by
// looking around it, compared with the map's; on a mismatch the map's rule for the QOC measured
// says at which corner to hold the wrong landmark and what to seek from there.

#include <fmt/format.h>

#include <algorithm>

#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {
namespace {

// Rules lead back in at most a few hops (the map-maker checks chains of up to 8); more is a loop.
constexpr int kMaxRecoveryHops = 8;

}  // namespace

std::optional<Failure> measure_qoc(Pilot& pilot, Hold& hold, Qoc& qoc) {
  // Visit the corners nearest first, so the look-around travels the least.
  std::vector<Corner> todo(kCorners.begin(), kCorners.end());
  qoc = Qoc{};
  const double margin = pilot.config().view_margin;
  while (!todo.empty()) {
    const auto next = std::min_element(todo.begin(), todo.end(), [&](Corner p, Corner q) {
      return (pilot.window().corner_point(p) - hold.landmark).squaredNorm() <
             (pilot.window().corner_point(q) - hold.landmark).squaredNorm();
    });
    hold.corner = *next;
    todo.erase(next);
    if (auto failure = adjust(pilot, hold.landmark, hold.corner)) return failure;
    // Held at this corner, the window shows the landmark's opposite quadrant: occupied when anything
    // else is in view (WorldViews::quadrants in the map-maker).
    const HeldView view = held_view(pilot.sighting(), hold, pilot.window(), pilot.heading(), margin);
    bool clearly = false;
    for (std::size_t i = 0; i < view.points.size(); ++i)
      clearly = clearly || (i != view.reference && view.depth[i] > margin);
    const bool seen = view.points.size() > 1;
    qoc.measured += seen;
    qoc.low += clearly;
    qoc.high += seen || !view.just_outside.empty();
    const auto q = static_cast<std::size_t>(index(opposite(hold.corner)));
    qoc.clearly[q] = clearly;
    qoc.maybe[q] = seen || !view.just_outside.empty();
  }
  return std::nullopt;
}

QuadrantPattern Qoc::pattern() const {
  QuadrantPattern p{};
  for (std::size_t q = 0; q < p.size(); ++q)
    p[q] = clearly[q] ? Occupancy::occupied : (maybe[q] ? Occupancy::unsure : Occupancy::empty);
  return p;
}

bool Qoc::agrees_with(const QuadrantPattern& map) const {
  for (std::size_t q = 0; q < map.size(); ++q) {
    if (map[q] == Occupancy::occupied && !maybe[q]) return false;
    if (map[q] == Occupancy::empty && clearly[q]) return false;
  }
  return true;
}

std::optional<Failure> verify(Pilot& pilot, const MapEntry& entry, bool doubtful, Eigen::Vector2d& landmark,
                              EntryRecord& record) {
  const std::optional<int> expected = entry.verified_qoc();
  const std::optional<QuadrantPattern> quadrants = pilot.config().quadrants ? entry.verified_quadrants() : std::nullopt;
  if (!expected) return std::nullopt;  // the map gives no QOC: nothing could be mistaken, or nothing told apart
  // A step nothing else could be taken for carries its landmark's QOC for when the view was not the
  // map-maker's and the navigator had to guess.
  // The goal is measured whenever the map gives its QOC: arriving at the wrong object is the one
  // mistake no later entry can show.
  if (entry.verify_only_in_doubt() && !doubtful && entry.adjust) return std::nullopt;
  Hold hold{landmark, Corner::SW};
  for (int hop = 0;; ++hop) {
    Qoc measured;
    if (auto failure = measure_qoc(pilot, hold, measured)) return failure;
    const int qoc = measured.measured;
    landmark = hold.landmark;
    record.measured_qoc = qoc;
    // Objects within the view margin of a border may lie on the other side for the map-maker: a QOC
    // it could have computed for this landmark verifies it, unless a rule names the QOC seen.
    const bool explained = measured.low <= *expected && *expected <= measured.high;
    const RecoveryRule* rule = pilot.config().recovery ? entry.recovery_for(qoc) : nullptr;
    // The quadrants, when the map names them, must agree too: the same count in other quadrants is
    // another marble (one the count alone would pass).
    const bool agrees = !quadrants || measured.agrees_with(*quadrants);
    if (agrees && (qoc == *expected || (explained && rule == nullptr))) {
      record.verified = true;
      return std::nullopt;
    }
    if (rule == nullptr || (qoc == *expected && !agrees)) {
      const std::string seen =
          agrees ? fmt::format("QOC {} where the map expects {}", qoc, *expected)
                 : fmt::format("quadrants {} where the map expects {} {}", format_quadrants(measured.pattern()),
                               *expected, format_quadrants(*quadrants));
      return Failure{Ending::unrecoverable,
                     fmt::format("the landmark reached has {}, and {}", seen,
                                 pilot.config().recovery ? "no recovery rule applies" : "recovery is off"),
                     true};
    }
    if (hop >= kMaxRecoveryHops) {
      return Failure{Ending::unrecoverable,
                     fmt::format("{} recovery rules applied without reaching QOC {}", hop, *expected), true};
    }
    hold.corner = *rule->corner;
    if (auto failure = adjust(pilot, hold.landmark, hold.corner)) return failure;
    SeekCandidate next;
    if (auto failure = seek(pilot, hold, rule->seek, 0, next)) return failure;
    hold.landmark = next.landmark;
    landmark = next.landmark;
    ++record.recoveries;
    ++pilot.report().recoveries;
    ++pilot.report().rule_recoveries;
  }
}

}  // namespace neopipe::nav::navigator::detail
