// Seek (park-kender.md §3): the landmark a description selects in the view of the held landmark,
// with the map-maker's own selection functions (nav/common/landmarks.hpp), so both choose alike.
// The view as seen may differ from the map-maker's: its positions have errors, so an object near a
// border may be on the other side for it. The candidates are therefore ranked, the description's
// choice first; the navigator takes the next one when the first leads nowhere (follow.cpp).

#include <fmt/format.h>

#include <algorithm>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

namespace {

// Indices into `depth` ordered deepest first (the most surely inside the map-maker's window).
std::vector<std::size_t> deepest_first(const std::vector<double>& depth, std::size_t skip) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (i != skip) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return depth[p] > depth[q]; });
  return order;
}

// Everything `description` could select in `view`, best first.
std::vector<SeekCandidate> seek_candidates(const HeldView& view, Description description, double margin) {
  std::vector<SeekCandidate> out;
  const std::size_t others = view.points.size() - 1;
  if (description == Description::Obvious) {
    // The map-maker saw exactly one object besides the reference. Seen so, it is certain; with one
    // clearly inside and others near a border, that one. With several clearly inside, the view is
    // not the one the map describes whatever the survey's errors: the landmark held is in doubt,
    // not this entry's choice, and there is no candidate. With none clearly inside, the one most
    // surely inside is the likeliest: a guess the navigator must confirm.
    std::size_t clear = 0;
    for (std::size_t i = 0; i < view.points.size(); ++i) clear += i != view.reference && view.depth[i] > margin;
    if (clear > 1) return out;
    const bool sure = others == 1 || clear == 1;
    for (const std::size_t i : deepest_first(view.depth, view.reference))
      out.push_back({view.points[i], !(sure && out.empty())});
  } else {
    const View v{view.points, view.reference};
    for (const std::size_t i : ranked_landmarks(description, v)) out.push_back({view.points[i], !out.empty()});
  }
  // Nothing (else) in view, but the map-maker saw something: objects just outside, likeliest first.
  for (const std::size_t i : deepest_first(view.outside_depth, view.outside_depth.size()))
    out.push_back({view.just_outside[i], true});
  // The only object anywhere near is no guess: nothing else could be taken for it.
  if (out.size() == 1) out.front().doubtful = false;
  return out;
}

}  // namespace

std::optional<Failure> seek(Pilot& pilot, const Hold& hold, Description description, int alternative,
                            SeekCandidate& found) {
  const double margin = pilot.config().view_margin;
  const HeldView view = held_view(pilot.sighting(), hold, pilot.window(), pilot.heading(), margin);
  const std::vector<SeekCandidate> candidates = seek_candidates(view, description, margin);
  const auto k = static_cast<std::size_t>(alternative);
  if (k >= candidates.size()) {
    if (alternative == 0) {
      return Failure{Ending::lost, fmt::format("no {} landmark in view ({} objects besides the reference)",
                                               description_name(description), view.points.size() - 1)};
    }
    return Failure{Ending::lost, fmt::format("no candidate #{} for the {} landmark ({} seen)", alternative + 1,
                                             description_name(description), candidates.size())};
  }
  found = candidates[k];
  return std::nullopt;
}

}  // namespace neopipe::nav::navigator::detail
