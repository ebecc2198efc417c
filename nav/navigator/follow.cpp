// The custom-map interpreter (park-kender.md §8): each entry (D, [T], [E], M) is seek D, slide
// along T, verify and recover by E, adjust to M; the goal's entry (M = '-') ends once the goal is
// identified and verified, without adjusting, as the map-maker's arrival edges assume.
//
// Recovery from a dead end: the survey's errors can make an entry's choice wrong in a way its QOC
// does not show (no QOC, or the same one), and then the next entry finds nothing it describes. The
// navigator remembers where it held each landmark (the moves it commanded since) and goes back: to
// the landmark held before the entry that failed, to take that entry's next candidate when its QOC
// proved the landmark wrong, or else to the one held before the previous entry, to take the
// previous entry's next candidate (the same slide with the window beside the track on either side,
// by one and two offsets, then the second object to enter it; the next most isolated; the next
// object of an Obvious view).
// A depth-first search over candidates, bounded per entry and per journey.

#include <fmt/format.h>

#include <Eigen/Geometry>

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

// A slide's k-th candidate: the first newcomer on the map's track, then (when the navigator has an
// offset) the first newcomer with the window moved beside the track on one side and the other, by
// the offset and then by twice it, then the track of the description's next landmark (a direction
// taken from the wrong one misses the goal by more than any offset), then the later newcomers on the
// track.
struct SlideTry {
  int skip = 0;
  double offset = 0;
  int direction_candidate = 0;  ///< which landmark the description selects gives the direction
};
SlideTry slide_try(int candidate, double offset) {
  if (offset <= 0 || candidate == 0) return {candidate, 0.0, 0};
  if (candidate <= 4) {
    const int times = (candidate + 1) / 2;  // 1, 1, 2, 2: one offset away, then two
    return {0, (candidate % 2 == 1 ? offset : -offset) * times, 0};
  }
  if (candidate == 5) return {0, 0.0, 1};
  return {candidate - 5, 0.0, 0};
}

std::optional<Failure> follow_entry(Pilot& pilot, const MapEntry& entry, int candidate, detail::Hold& held,
                                    EntryRecord& record) {
  detail::SeekCandidate sought{held.landmark, false};
  // A slide's candidates are its tries (slide_try); a landmark's, the description's next choices.
  const SlideTry t = slide_try(candidate, pilot.config().slide_offset);
  if (auto failure = detail::seek(pilot, held, entry.seek, entry.slide ? t.direction_candidate : candidate, sought))
    return failure;
  Eigen::Vector2d landmark = sought.landmark;
  bool doubtful = sought.doubtful;
  if (entry.slide) {
    Eigen::Vector2d found = landmark;
    if (auto failure = detail::slide(pilot, held, landmark, entry, t.skip, t.offset, found)) return failure;
    landmark = found;
    // A later try's newcomer is a guess, unless it entered where the map says the goal does.
    doubtful = entry.slide_goal && pilot.config().slide_goals ? false : doubtful || candidate > 0;
  }
  if (auto failure = detail::verify(pilot, entry, doubtful, landmark, record)) return failure;
  if (doubtful && !entry.adjust && !record.verified) {
    // The goal taken by a guess that nothing confirms would be an unaware failure in one case of two.
    return Failure{Ending::lost, "the goal could not be told apart (the view was not the map's, and it has no QOC)",
                   true};
  }
  if (entry.adjust) {
    if (auto failure = detail::adjust(pilot, landmark, *entry.adjust)) return failure;
    held.corner = *entry.adjust;
  }
  held.landmark = landmark;
  return std::nullopt;
}

// Where the navigator held a landmark after an entry, and the moves it had commanded by then.
struct Checkpoint {
  detail::Hold held;
  Eigen::Vector2d odometry;
};

// Undoes the moves since `to` and holds its landmark again (the nearest object to where it was).
std::optional<Failure> return_to(Pilot& pilot, const Checkpoint& to, detail::Hold& held) {
  const Eigen::Vector2d back = Eigen::Rotation2Dd(-pilot.heading()) * (to.odometry - pilot.odometry());
  pilot.move_and_look(back);
  if (!pilot.moved()) return Failure{Ending::lost, "cannot go back to an earlier landmark: beyond the arm's reach"};
  const std::vector<Eigen::Vector2d> seen = detail::everything_seen(pilot.sighting());
  const auto i = detail::nearest(seen, to.held.landmark, detail::tracking_gate(back.norm()));
  if (!i) return Failure{Ending::lost, "went back to an earlier landmark and did not find it"};
  held = to.held;
  held.landmark = seen[*i];
  return detail::adjust(pilot, held.landmark, held.corner);
}

// How many entries back a dead end may send the navigator: a wrong landmark is usually found out
// by the next entry or the one after (an Obvious view that happens to hold one object passes).
constexpr std::size_t kMaxBacktrackDepth = 3;

// The entry to take the next candidate of after entry `failed` failed, if any is left (chronological
// backtracking): the failed entry itself when its landmark was proved wrong, else the latest entry
// before it, up to kMaxBacktrackDepth back, that has a candidate left.
std::optional<std::size_t> entry_to_redo(std::size_t failed, const Failure& failure, const std::vector<int>& candidate,
                                         int max_alternatives) {
  if (failure.wrong_candidate && candidate[failed] < max_alternatives) return failed;
  for (std::size_t j = failed - 1; j >= 1 && failed - j <= kMaxBacktrackDepth; --j) {
    if (candidate[j] < max_alternatives) return j;
  }
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
  const std::size_t n = map.entries.size();
  detail::Hold held{Eigen::Vector2d::Zero(), Corner::SW};
  std::vector<Checkpoint> checkpoints;  // [i]: after entry i
  std::vector<int> candidate(n, 0);
  const auto fail = [&](std::size_t i, const Failure& failure) {
    report.ending = failure.ending;
    report.reason = fmt::format("entry {} {}: {}", i, format_entry(map.entries[i]), failure.reason);
    return report;
  };
  for (std::size_t i = 0; i < n;) {
    EntryRecord record;
    record.entry = i;
    record.candidate = candidate[i];
    const std::int64_t frames_before = report.frames;
    std::optional<Failure> failure = i == 0 ? take_start(pilot, map.entries[i], held)
                                            : follow_entry(pilot, map.entries[i], candidate[i], held, record);
    record.frames = report.frames - frames_before;
    report.entries.push_back(record);
    if (!failure) {
      checkpoints.resize(i);
      checkpoints.push_back({held, pilot.odometry()});
      if (observer != nullptr) observer->landmark_held(i, held.landmark);
      ++i;
      continue;
    }
    const auto redo = config.recovery && i > 0 && report.backtracks < config.max_backtracks
                          ? entry_to_redo(i, *failure, candidate, config.max_alternatives)
                          : std::nullopt;
    if (!redo) return fail(i, *failure);
    ++candidate[*redo];
    for (std::size_t j = *redo + 1; j < n; ++j) candidate[j] = 0;
    if (auto lost = return_to(pilot, checkpoints[*redo - 1], held)) return fail(i, *lost);
    ++report.backtracks;
    ++report.recoveries;
    i = *redo;
  }
  report.ending = Ending::arrived;
  return report;
}

}  // namespace neopipe::nav::navigator
