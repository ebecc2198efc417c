#pragma once
// The picture of `neopipe map stats`: the paper's Fig. 7 (parkways against population, one curve per
// window, with the Poisson estimate dashed; obvious/isolated/general parkways for one window) and
// Fig. 11 (strongly connected components without and with trajectories), with 95% CI bars.

#include <string>
#include <vector>

#include "nav/mapmaker/statistics.hpp"

namespace neopipe::apps {

/// Writes a PNG to `path`; throws std::runtime_error naming the path when it cannot.
void write_map_stats_plot(const std::vector<nav::mapmaker::StatisticsRow>& rows, const std::string& path);

}  // namespace neopipe::apps
