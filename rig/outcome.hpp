#pragma once
// The six navigation outcomes of park-kender.md §9, assigned by the rig (never by a navigator) from
// what the navigator reports plus the ground truth, and the statistics of many journeys. They apply
// to every navigation system the rig runs: each ends aware of a failure, or believing it arrived.

#include <array>
#include <cstdint>
#include <string_view>

namespace neopipe::rig {

/// How a journey ended, as the navigator knows it.
enum class Ending : std::uint8_t {
  arrived,        ///< followed its directions to the end; believes it is at the goal
  lost,           ///< could not find what its directions describe (aware failure 1)
  unrecoverable,  ///< detected an error it cannot fix (aware failure 2)
};

std::string_view ending_name(Ending e);

enum class Outcome : std::uint8_t {
  success_direct,      ///< arrived at the goal, every step correct, no recovery needed
  success_recovered,   ///< arrived at the goal after recovery rules put it back on the path
  success_unaware,     ///< arrived at the goal although some step held a wrong landmark unnoticed
  fail_lost,           ///< stopped: could not find what the directions describe (aware)
  fail_unrecoverable,  ///< stopped: detected an error that no rule fixes (aware)
  fail_unaware,        ///< believes it arrived, but holds something other than the goal
};

inline constexpr std::array<Outcome, 6> kOutcomes{Outcome::success_direct,     Outcome::success_recovered,
                                                  Outcome::success_unaware,    Outcome::fail_lost,
                                                  Outcome::fail_unrecoverable, Outcome::fail_unaware};

std::string_view outcome_name(Outcome o);
bool reached_goal(Outcome o);  ///< the three successes

/// What the rig knows at the end of a journey: the navigator's own account and the truth.
struct JourneyTruth {
  Ending ending = Ending::arrived;
  int recoveries = 0;               ///< recovery rules the navigator applied
  bool goal_held = false;           ///< the last landmark it held is really the goal
  bool every_step_correct = false;  ///< at every entry it held the landmark its plan meant
};

Outcome classify(const JourneyTruth& truth);

/// A 95% (z = 1.96) Wilson score interval for a binomial proportion k / n; [0, 1] when n = 0.
struct Interval {
  double low = 0;
  double high = 1;
};
Interval wilson_interval(std::int64_t successes, std::int64_t trials, double z = 1.959963984540054);

/// The exact two-sided McNemar (sign) test: the probability, if both runs were equally good, of a
/// split of the discordant journeys at least as uneven as `a_only` against `b_only`.
double mcnemar_p(std::int64_t a_only, std::int64_t b_only);

}  // namespace neopipe::rig
