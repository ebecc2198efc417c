#include "nav/mapmaker/verification.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace neopipe::nav::mapmaker {

std::string_view verifiability_name(Verifiability v) {
  constexpr std::array<std::string_view, 4> names{"trivial", "correctable", "not_correctable", "unverifiable"};
  return names[static_cast<std::size_t>(v)];
}

std::vector<std::uint32_t> confusable_in_view(const WorldViews& views, const Placement& from, std::uint32_t landmark,
                                              Description description) {
  std::vector<std::uint32_t> out;
  if (description == Description::Obvious) return out;
  for (const std::uint32_t id : views.visible(from)) {
    if (id != from.object && id != landmark) out.push_back(id);
  }
  return out;
}

std::vector<std::uint32_t> confusable_on_trajectory(const WorldViews& views, const Trajectory& trajectory,
                                                    const NavigatorErrors& errors) {
  std::set<std::uint32_t> out;
  for (const std::uint32_t id : confusable_in_view(views, trajectory.from, trajectory.via, trajectory.description)) {
    out.insert(id);
  }
  const Eigen::Vector2d& p1 = views.position(trajectory.from.object);
  const double baseline = (views.position(trajectory.via) - p1).norm();
  const double slide = std::max(trajectory.slide, 1e-9);
  const double static_sd = std::sqrt(2.0) * errors.sigma / baseline;
  const double dynamic_sd = std::hypot(errors.rotation_per_mm * slide / 2, errors.translation_per_mm);
  const double spread = 3 * std::hypot(static_sd, dynamic_sd);
  const Eigen::Vector2d heading = trajectory.heading(views);
  const double angle = std::atan2(heading.y(), heading.x());
  constexpr int samples = 61;
  for (int i = 0; i < samples; ++i) {
    const double a = angle + spread * (2.0 * i / (samples - 1) - 1.0);
    const auto hit = first_entering(views.grid(), views.window(), views.origin(trajectory.from),
                                    Eigen::Vector2d(std::cos(a), std::sin(a)), p1);
    if (hit && hit->object != trajectory.to) out.insert(hit->object);
  }
  out.erase(trajectory.to);
  return {out.begin(), out.end()};
}

namespace {

// What the navigator may measure at each object: a QOC anywhere in the object's range.
class QocRanges {
 public:
  QocRanges(const WorldViews& views, double tolerance) : views_(views), tolerance_(tolerance) {}
  QocRange operator()(std::uint32_t id) const { return views_.qoc_range(id, tolerance_); }

 private:
  const WorldViews& views_;
  double tolerance_;
};

// Whether the rule table takes the navigator from `at`, where it measured `measured`, to `landmark`
// whatever it measures at the objects it passes (every QOC in their ranges), within `hops` rules.
bool leads_back(const WorldViews& views, const QocRanges& ranges, std::uint32_t landmark, const QocRange& mine,
                std::uint32_t at, int measured, const std::map<int, Corner>& rules, int hops = 8) {
  if (at == landmark) return true;
  if (hops == 0) return false;
  const auto rule = rules.find(measured);
  if (rule == rules.end()) return false;
  const auto next = views.isolated({at, rule->second});
  if (!next) return false;
  if (*next == landmark) return true;
  const QocRange there = ranges(*next);
  if (there.overlaps(mine)) return false;  // would pass verification at the wrong place
  for (int q = there.low; q <= there.high; ++q) {
    if (!leads_back(views, ranges, landmark, mine, *next, q, rules, hops - 1)) return false;
  }
  return true;
}

}  // namespace

StepCheck check_step(const WorldViews& views, std::uint32_t landmark, std::span<const std::uint32_t> confusable,
                     double tolerance) {
  StepCheck check;
  check.qoc = views.qoc(landmark);
  check.confusable.assign(confusable.begin(), confusable.end());
  std::sort(check.confusable.begin(), check.confusable.end());
  const QocRanges ranges(views, tolerance);
  const QocRange mine = ranges(landmark);
  if (check.confusable.empty()) {  // trivial: the QOC, for when the navigator's view makes it guess
    if (mine.low == mine.high) check.rules.push_back(RecoveryRule::verified(check.qoc, true));
    return check;
  }
  // Every QOC a mistaken object may show, with the objects that may show it.
  std::map<int, std::vector<std::uint32_t>> by_qoc;
  for (const std::uint32_t id : check.confusable) {
    const QocRange r = ranges(id);
    if (r.overlaps(mine)) {
      check.kind = Verifiability::unverifiable;
      return check;
    }
    for (int q = r.low; q <= r.high; ++q) by_qoc[q].push_back(id);
  }
  // One rule per QOC value. Rules that take their objects straight back are found first; a second
  // and third pass allow chains through rules already chosen (paper: C -> B -> I).
  std::map<int, Corner> rules;
  for (int pass = 0; pass < 3; ++pass) {
    for (const auto& [qoc, objects] : by_qoc) {
      const int q = qoc;  // a plain variable: lambdas capture structured bindings only since C++20
      if (rules.count(q)) continue;
      for (const Corner c : kCorners) {
        std::map<int, Corner> trial = rules;
        trial[q] = c;
        const bool all = std::all_of(objects.begin(), objects.end(), [&](std::uint32_t id) {
          return leads_back(views, ranges, landmark, mine, id, q, trial);
        });
        if (all) {
          rules = std::move(trial);
          break;
        }
      }
    }
  }
  const bool correctable =
      rules.size() == by_qoc.size() && std::all_of(by_qoc.begin(), by_qoc.end(), [&](const auto& e) {
        return std::all_of(e.second.begin(), e.second.end(), [&](std::uint32_t id) {
          return leads_back(views, ranges, landmark, mine, id, e.first, rules);
        });
      });
  check.kind = correctable ? Verifiability::correctable : Verifiability::not_correctable;
  if (correctable) {
    for (const auto& [q, c] : rules) check.rules.push_back(RecoveryRule::leading_back(q, c, Description::Isol));
  }
  check.rules.push_back(RecoveryRule::verified(check.qoc));
  return check;
}

std::string verification_line(const StepCheck& check) {
  switch (check.kind) {
    case Verifiability::trivial:
      return fmt::format("VERIFY QOC -> {} (TRIVIAL CASE)", check.qoc);
    case Verifiability::unverifiable:
      return "UNVERIFIABLE (Not Correctable)";
    case Verifiability::not_correctable:
      return fmt::format("VERIFY QOC -> {} (NOT CORRECTABLE)", check.qoc);
    case Verifiability::correctable:
      break;
  }
  std::string line = fmt::format("VERIFY QOC -> {} (CORRECTABLE)", check.qoc);
  for (const RecoveryRule& r : check.rules) {
    if (r.corner) line += fmt::format(" IF QOC -> {} ({}, {})", r.qoc, corner_name(*r.corner), "ISOL");
  }
  return line;
}

}  // namespace neopipe::nav::mapmaker
