#include "nav/mapmaker/steps.hpp"

#include <algorithm>
#include <cmath>

#include "nav/mapmaker/view_agreement.hpp"

namespace neopipe::nav::mapmaker {

double Step::unreliability() const {
  return reliability >= 1 ? 0.0 : -std::log(std::max(reliability, 1e-300));
}

StepTable::StepTable(const WorldViews& views, const NavigatorErrors& errors, bool extended) {
  const auto nodes = static_cast<std::uint32_t>(4 * views.object_count());
  first_.reserve(nodes + 1);
  first_.push_back(0);
  std::vector<Step> group;
  for (std::uint32_t node = 0; node < nodes; ++node) {
    const Placement from = Placement::of_node(node);
    const Eigen::Vector2d start = views.origin(from);
    const Eigen::Vector2d reference = views.position(from.object);
    const int visible = static_cast<int>(views.visible(from).size());
    group.clear();
    const auto add = [&](Step s, const Eigen::Vector2d& found_at) {
      s.landmark_distance = (views.position(s.landmark) - reference).norm();
      for (const Corner m : kCorners) {
        s.adjust = m;
        s.travel = s.arrival_travel + (views.origin({s.landmark, m}) - found_at).norm();
        group.push_back(s);
      }
    };
    const bool obvious = views.obvious(from).has_value();
    const Description primary = obvious ? Description::Obvious : Description::Isol;
    const auto landmark_of_primary = views.landmark(from, primary);
    for (const Description seek : {primary, Description::Far, Description::Near}) {
      const auto landmark = views.landmark(from, seek);
      if (!landmark) continue;
      // Far and Near only where they name an object no earlier description does.
      if (seek != primary) {
        if (!extended || obvious || landmark == landmark_of_primary) continue;
        if (seek == Description::Near && landmark == views.landmark(from, Description::Far)) continue;
      }
      const double selection = seek == primary ? selection_reliability(visible, errors.sigma, views.window().side) *
                                                     view_agreement(views, from, seek, errors.sigma)
                                               : distance_rank_reliability(views, from, seek, errors.sigma);
      Step s;
      s.from = from;
      s.landmark = s.via = *landmark;
      s.seek = seek;
      s.visible = visible;
      s.reliability = selection;
      s.forecast = errors.recovery.rated(s.reliability);
      add(s, start);
      for (const Direction dir : {Direction::positive, Direction::negative}) {
        const auto t = trajectory_from(views, from, seek, dir);
        if (!t) continue;
        trajectories_.push_back(*t);
        Step ts = s;
        ts.landmark = t->to;
        ts.slide = dir;
        ts.arrival_travel = t->slide;
        ts.reliability =
            selection * trajectory_reliability(views, *t, errors) * entry_order_agreement(views, *t, errors.sigma);
        ts.forecast = errors.recovery.rated(ts.reliability);
        add(ts, start + t->slide * t->heading(views));
      }
    }
    std::stable_sort(group.begin(), group.end(),
                     [](const Step& a, const Step& b) { return a.landmark_distance > b.landmark_distance; });
    steps_.insert(steps_.end(), group.begin(), group.end());
    first_.push_back(static_cast<std::uint32_t>(steps_.size()));
  }
}

}  // namespace neopipe::nav::mapmaker
