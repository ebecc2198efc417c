#include "apps/outcome_table.hpp"

#include <fmt/format.h>

#include <string_view>

#include "rig/outcome.hpp"

namespace neopipe::apps {

void print_outcome_rows(std::ostream& out, const rig::TrialsSummary& t, std::int64_t journeys_run) {
  const auto row = [&](std::string_view name, std::int64_t count) {
    const rig::Interval w = rig::wilson_interval(count, journeys_run);
    out << fmt::format("{:<20} {:>7} {:>7.2f}%  [{:.2f}%, {:.2f}%]\n", name, count,
                       100.0 * static_cast<double>(count) / static_cast<double>(journeys_run), 100 * w.low,
                       100 * w.high);
  };
  for (const rig::Outcome o : rig::kOutcomes) row(rig::outcome_name(o), t.count(o));
  row("reached the goal", t.reached());
}

}  // namespace neopipe::apps
