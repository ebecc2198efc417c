// The custom-map interpreter (park-kender.md §8): each entry (D, [T], [E], M) is seek D, slide
// along T, verify and recover by E, adjust to M; the goal's entry (M = '-') ends once the goal is
// identified and verified, without adjusting, as the map-maker's arrival edges assume.

#include <fmt/format.h>

#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator {

using detail::Failure;
using detail::Pilot;

namespace {

std::optional<Failure> take_start(Pilot& pilot, const MapEntry& entry, detail::Hold& held) {
  // (*, c): the harness placed the start object at c. Whatever lies nearest that corner is it.
  held.corner = entry.adjust.value_or(Corner::SW);
  const std::vector<Eigen::Vector2d> seen = detail::everything_seen(pilot.look());
  const Eigen::Vector2d corner = pilot.window().corner_point(held.corner);
  const auto start = detail::nearest(seen, corner, 2 * detail::tracking_gate(0));
  if (!start)
    return Failure{Ending::lost, fmt::format("no object held at the start corner {}", corner_name(held.corner))};
  held.landmark = seen[*start];
  return detail::adjust(pilot, held.landmark, held.corner);
}

std::optional<Failure> follow_entry(Pilot& pilot, const MapEntry& entry, detail::Hold& held, EntryRecord& record) {
  Eigen::Vector2d landmark = held.landmark;
  if (auto failure = detail::seek(pilot, held, entry.seek, landmark)) return failure;
  if (entry.slide) {
    Eigen::Vector2d found = landmark;
    if (auto failure = detail::slide(pilot, held, landmark, *entry.slide, found)) return failure;
    landmark = found;
  }
  if (auto failure = detail::verify(pilot, entry, landmark, record)) return failure;
  if (entry.adjust) {
    if (auto failure = detail::adjust(pilot, landmark, *entry.adjust)) return failure;
    held.corner = *entry.adjust;
  }
  held.landmark = landmark;
  return std::nullopt;
}

}  // namespace

JourneyReport follow(const CustomMap& map, Eye& eye, Arm& arm, const NavigatorConfig& config, Observer* observer) {
  JourneyReport report;
  Pilot pilot(eye, arm, config, observer, report);
  if (map.entries.empty()) {
    report.ending = Ending::lost;
    report.reason = "the custom map has no entries";
    return report;
  }
  detail::Hold held{Eigen::Vector2d::Zero(), Corner::SW};
  for (std::size_t i = 0; i < map.entries.size(); ++i) {
    EntryRecord record;
    record.entry = i;
    const std::int64_t frames_before = report.frames;
    const std::optional<Failure> failure =
        i == 0 ? take_start(pilot, map.entries[i], held) : follow_entry(pilot, map.entries[i], held, record);
    record.frames = report.frames - frames_before;
    report.entries.push_back(record);
    if (failure) {
      report.ending = failure->ending;
      report.reason = fmt::format("entry {} {}: {}", i, format_entry(map.entries[i]), failure->reason);
      return report;
    }
    if (observer != nullptr) observer->landmark_held(i, held.landmark);
  }
  report.ending = Ending::arrived;
  return report;
}

}  // namespace neopipe::nav::navigator
