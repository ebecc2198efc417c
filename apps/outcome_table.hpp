#pragma once
// The outcome table `neopipe nav --trials N` prints for every system: a row per outcome and one for
// the goal reached, each with its count, rate and Wilson 95 % interval over the journeys run.

#include <cstdint>
#include <ostream>

#include "rig/trials.hpp"

namespace neopipe::apps {

void print_outcome_rows(std::ostream& out, const rig::TrialsSummary& t, std::int64_t journeys_run);

}  // namespace neopipe::apps
