// Seek (park-kender.md §3): the landmark a description selects in the view of the held landmark,
// with the map-maker's own selection functions (nav/common/landmarks.hpp), so both choose alike.
// The view as seen may differ from the map-maker's: its positions have errors, so an object near a
// border may be on the other side for it. The candidates are therefore ranked, the description's
// choice first; the navigator takes the next one when the first leads nowhere (follow.cpp). When
// the view shows too few, the window looks beyond its far edges, where the camera cannot see but
// the map-maker's errors may have put an object inside.

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <utility>

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

// Objects the map-maker may have seen in the window that lie beyond its far edges (those away from
// the held corner), where the camera cannot see them: the window moves away from the corner by
// `reach` across each far edge in turn, looks, and comes back. Positions are in the held window's
// coordinates, the nearest to the window first; objects already `listed` are left out.
std::optional<Failure> beyond_far_edges(Pilot& pilot, const Hold& hold, double reach,
                                        std::vector<Eigen::Vector2d> listed, std::vector<Eigen::Vector2d>& found) {
  const WindowModel& window = pilot.window();
  const Eigen::Vector2d corner = window.corner_point(hold.corner);
  const Eigen::Vector2d outward = (Eigen::Vector2d::Constant(window.side / 2) - corner).cwiseSign() * reach;
  const Eigen::Rotation2Dd unturn(pilot.heading());
  listed.push_back(hold.landmark);
  std::vector<std::pair<double, Eigen::Vector2d>> beyond;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Vector2d across_edge = Eigen::Vector2d::Zero();
    across_edge[axis] = outward[axis];
    const Eigen::Vector2d move = unturn.inverse() * across_edge;  // in the real window's axes
    const std::vector<Eigen::Vector2d> seen = everything_seen(pilot.move_and_look(move));
    const bool moved = pilot.moved();
    for (const Eigen::Vector2d& p : moved ? seen : std::vector<Eigen::Vector2d>{}) {
      const Eigen::Vector2d at = p + move;  // where it is in the held window's coordinates
      const Eigen::Vector2d exact = corner + unturn * (at - hold.landmark);
      const double depth = std::min({exact.x(), exact.y(), window.side - exact.x(), window.side - exact.y()});
      const bool known = std::any_of(listed.begin(), listed.end(),
                                     [&](const Eigen::Vector2d& q) { return (at - q).norm() < tracking_gate(reach); });
      if (known || depth > 0 || depth <= -reach) continue;
      beyond.emplace_back(-depth, at);
      listed.push_back(at);
    }
    if (!moved) continue;  // beyond the arm's reach: nothing to see there
    pilot.move_and_look(-move);
    if (!pilot.moved()) return Failure{Ending::lost, "cannot come back from a look beyond the window's edges"};
  }
  std::stable_sort(beyond.begin(), beyond.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  for (const auto& b : beyond) found.push_back(b.second);
  return std::nullopt;
}

}  // namespace

std::optional<Failure> seek(Pilot& pilot, const Hold& hold, Description description, int alternative,
                            SeekCandidate& found) {
  const double margin = pilot.config().view_margin;
  const HeldView view = held_view(pilot.sighting(), hold, pilot.window(), pilot.heading(), margin);
  std::vector<SeekCandidate> candidates = seek_candidates(view, description, margin);
  const auto k = static_cast<std::size_t>(alternative);
  if (k >= candidates.size() && margin > 0 && !(description == Description::Obvious && view.points.size() > 2)) {
    // Too few candidates in sight: the map-maker's may lie beyond the far edges, a guess to confirm.
    std::vector<Eigen::Vector2d> listed = view.just_outside;
    for (const SeekCandidate& c : candidates) listed.push_back(c.landmark);
    std::vector<Eigen::Vector2d> beyond;
    if (auto failure = beyond_far_edges(pilot, hold, margin, listed, beyond)) return failure;
    for (const Eigen::Vector2d& p : beyond) candidates.push_back({p, true});
  }
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
