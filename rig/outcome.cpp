#include "rig/outcome.hpp"

#include <algorithm>
#include <cmath>

namespace neopipe::rig {

std::string_view ending_name(Ending e) {
  constexpr std::array<std::string_view, 3> names{"arrived", "lost", "unrecoverable"};
  return names[static_cast<std::size_t>(e)];
}

std::string_view outcome_name(Outcome o) {
  constexpr std::array<std::string_view, 6> names{"success_direct", "success_recovered",  "success_unaware",
                                                  "fail_lost",      "fail_unrecoverable", "fail_unaware"};
  return names[static_cast<std::size_t>(o)];
}

bool reached_goal(Outcome o) {
  return o == Outcome::success_direct || o == Outcome::success_recovered || o == Outcome::success_unaware;
}

Outcome classify(const JourneyTruth& t) {
  if (t.ending == Ending::lost) return Outcome::fail_lost;
  if (t.ending == Ending::unrecoverable) return Outcome::fail_unrecoverable;
  if (!t.goal_held) return Outcome::fail_unaware;
  // At the goal. A wrong landmark held at some entry that the navigator never noticed makes the
  // success an unaware one even if recovery also happened elsewhere: the path was not the plan's.
  if (!t.every_step_correct) return Outcome::success_unaware;
  return t.recoveries > 0 ? Outcome::success_recovered : Outcome::success_direct;
}

Interval wilson_interval(std::int64_t successes, std::int64_t trials, double z) {
  if (trials <= 0) return {};
  const auto n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double denominator = 1 + z2 / n;
  const double centre = (p + z2 / (2 * n)) / denominator;
  const double half = z / denominator * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

double mcnemar_p(std::int64_t a_only, std::int64_t b_only) {
  const std::int64_t n = a_only + b_only;
  if (n <= 0) return 1;
  const std::int64_t k = std::min(a_only, b_only);
  // 2 * P(X <= k), X ~ Binomial(n, 1/2), summed in logs so that thousands of journeys do not
  // overflow a binomial coefficient.
  double tail = 0;
  for (std::int64_t i = 0; i <= k; ++i) {
    const double log_term = std::lgamma(static_cast<double>(n) + 1) - std::lgamma(static_cast<double>(i) + 1) -
                            std::lgamma(static_cast<double>(n - i) + 1) - static_cast<double>(n) * std::log(2.0);
    tail += std::exp(log_term);
  }
  return std::min(1.0, 2 * tail);
}

}  // namespace neopipe::rig
