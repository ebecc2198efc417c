#pragma once
// The reliability diagram of `neopipe nav --trials N --reliability-diagram F.png`: journeys grouped
// in bins of the map-maker's forecast, each bin's mean forecast against the share that reached the
// goal with its 95% Wilson interval. A forecast to be trusted puts every bin on the diagonal.

#include <string>
#include <vector>

namespace neopipe::apps {

struct ForecastOutcome {
  double forecast = 1;   ///< the planned reliability R of the journey's route
  bool reached = false;  ///< it reached the goal
};

struct ForecastBin {
  double low = 0, high = 1;  ///< forecasts in [low, high)
  int journeys = 0;
  int reached = 0;
  double mean_forecast = 0;
  double ci_low = 0, ci_high = 1;  ///< 95% Wilson interval of the observed rate
};

/// The bins of the diagram: < 0.8, 0.8-0.9, 0.9-0.97, >= 0.97.
std::vector<ForecastBin> forecast_bins(const std::vector<ForecastOutcome>& journeys);

/// Writes the diagram (PNG, or any format the media plug-in writes) to `path`, titled `title`;
/// throws std::runtime_error naming the path when it cannot.
void write_reliability_diagram(const std::vector<ForecastOutcome>& journeys, const std::string& title,
                               const std::string& path);

}  // namespace neopipe::apps
