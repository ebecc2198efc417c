#pragma once
// The map-maker's picture: the world, its parkways and trajectories, and a planned route with the
// window at each placement, like the paper's figures. Drawn once as primitives, written as SVG or
// rendered to PNG by OpenCV, so both show the same thing.

#include <optional>
#include <string>

#include "nav/mapmaker/map_maker.hpp"

namespace neopipe::apps {

/// Writes the plot to `path` (.svg or .png; anything else is an error naming the path).
void write_map_plot(const nav::mapmaker::MapMaker& maker, const std::optional<nav::mapmaker::Route>& route,
                    const std::string& path);

}  // namespace neopipe::apps
