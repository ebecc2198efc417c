#pragma once
// Parkways (park-kender.md §3, paper §4.1-4.3): graphs on the objects whose edges the navigator
// can travel keeping its target in view. General parkways are undirected components; the obvious
// and isolated parkways are directed, one edge per (object, corner) at most.

#include <cstdint>
#include <span>
#include <vector>

#include "nav/common/window.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

/// R -> `to` when `to` is the landmark seen with R held at `corner`.
struct ParkwayEdge {
  std::uint32_t from = 0;
  Corner corner = Corner::SW;
  std::uint32_t to = 0;
  friend bool operator==(const ParkwayEdge&, const ParkwayEdge&) = default;
};

/// General parkways: connected components of "one window can hold both". Each component's ids
/// ascending; components ordered by their smallest id. Uses the grid: O(n k).
std::vector<std::vector<std::uint32_t>> general_parkways(const WorldViews& views);

/// Edges R -> B whenever B is the obvious landmark for R at some corner, by (R, corner).
std::vector<ParkwayEdge> obvious_parkway(const WorldViews& views);

/// Edges R -> I whenever I is the isolated landmark for R at some corner, by (R, corner).
std::vector<ParkwayEdge> isolated_parkway(const WorldViews& views);

/// Strongly connected components of a directed graph on `nodes` nodes given as (from, to) pairs:
/// each component's nodes ascending, components ordered by smallest node. Iterative (no recursion
/// depth limit on 100,000-object worlds).
std::vector<std::vector<std::uint32_t>> strongly_connected_components(
    std::size_t nodes, std::span<const std::pair<std::uint32_t, std::uint32_t>> edges);

}  // namespace neopipe::nav::mapmaker
