#pragma once
// The map-maker's picture: the world, its parkways and trajectories, and a planned route with the
// window at each placement, like the paper's figures. Drawn once as primitives, written as SVG or
// rendered to PNG by OpenCV, so both show the same thing.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "nav/mapmaker/map_maker.hpp"

namespace neopipe::apps {

/// What the navigator really did on a route (neopipe nav), drawn over the map-maker's plan.
struct ExecutedRoute {
  std::vector<Eigen::Vector2d> track;         ///< the window's true centre after each move, mm
  std::vector<Eigen::Vector2d> held_windows;  ///< true lower-left corners of the windows where it held a landmark
  std::string caption;                        ///< one line: the outcome
};

/// Writes the plot to `path` (.svg or .png; anything else is an error naming the path).
void write_map_plot(const nav::mapmaker::MapMaker& maker, const std::optional<nav::mapmaker::Route>& route,
                    const std::string& path, const ExecutedRoute* executed = nullptr);

}  // namespace neopipe::apps
