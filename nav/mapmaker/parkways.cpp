#include "nav/mapmaker/parkways.hpp"

#include <algorithm>
#include <numeric>

namespace neopipe::nav::mapmaker {
namespace {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the root is the smallest id
  }

 private:
  std::vector<std::uint32_t> parent_;
};

std::vector<std::vector<std::uint32_t>> group_by_root(std::span<const std::uint32_t> root) {
  // Components in order of their smallest member; members ascending.
  std::vector<std::vector<std::uint32_t>> groups;
  std::vector<std::int64_t> slot(root.size(), -1);
  for (std::uint32_t i = 0; i < root.size(); ++i) {
    if (slot[root[i]] < 0) {
      slot[root[i]] = static_cast<std::int64_t>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(slot[root[i]])].push_back(i);
  }
  return groups;
}

std::vector<ParkwayEdge> landmark_edges(const WorldViews& views, Description description) {
  std::vector<ParkwayEdge> edges;
  for (std::uint32_t node = 0; node < 4 * views.object_count(); ++node) {
    const Placement p = Placement::of_node(node);
    if (const auto to = views.landmark(p, description)) edges.push_back({p.object, p.corner, *to});
  }
  return edges;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> general_parkways(const WorldViews& views) {
  const std::size_t n = views.object_count();
  DisjointSets sets(n);
  const double reach = views.window().side - 2 * views.window().margin;
  const Eigen::Vector2d r(reach, reach);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = views.position(i);
    views.grid().for_each_near(p - r, p + r, [&](std::uint32_t j) {
      if (j > i && views.window().fit_together(p, views.position(j))) sets.join(i, j);
    });
  }
  std::vector<std::uint32_t> root(n);
  for (std::uint32_t i = 0; i < n; ++i) root[i] = sets.find(i);
  return group_by_root(root);
}

std::vector<ParkwayEdge> obvious_parkway(const WorldViews& views) {
  return landmark_edges(views, Description::Obvious);
}

std::vector<ParkwayEdge> isolated_parkway(const WorldViews& views) {
  return landmark_edges(views, Description::Isol);
}

std::vector<std::vector<std::uint32_t>> strongly_connected_components(
    std::size_t nodes, std::span<const std::pair<std::uint32_t, std::uint32_t>> edges) {
  // Tarjan's algorithm with an explicit stack.
  std::vector<std::uint32_t> first(nodes + 1, 0);
  for (const auto& [from, to] : edges) ++first[from + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::uint32_t> adjacent(edges.size());
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (const auto& [from, to] : edges) adjacent[fill[from]++] = to;
  }
  constexpr std::uint32_t unvisited = ~0u;
  std::vector<std::uint32_t> order(nodes, unvisited);
  std::vector<std::uint32_t> low(nodes, 0);
  std::vector<bool> on_stack(nodes, false);
  std::vector<std::uint32_t> stack;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> calls;  // (node, next edge)
  std::vector<std::uint32_t> root(nodes, 0);
  std::uint32_t counter = 0;
  for (std::uint32_t s = 0; s < nodes; ++s) {
    if (order[s] != unvisited) continue;
    calls.emplace_back(s, first[s]);
    order[s] = low[s] = counter++;
    stack.push_back(s);
    on_stack[s] = true;
    while (!calls.empty()) {
      auto& [v, next] = calls.back();
      if (next < first[v + 1]) {
        const std::uint32_t w = adjacent[next++];
        if (order[w] == unvisited) {
          order[w] = low[w] = counter++;
          stack.push_back(w);
          on_stack[w] = true;
          calls.emplace_back(w, first[w]);
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], order[w]);
        }
        continue;
      }
      const std::uint32_t done = v;
      calls.pop_back();
      if (!calls.empty()) low[calls.back().first] = std::min(low[calls.back().first], low[done]);
      if (low[done] == order[done]) {
        std::uint32_t smallest = done;
        const auto begin = std::find(stack.rbegin(), stack.rend(), done).base() - 1;
        for (auto it = begin; it != stack.end(); ++it) smallest = std::min(smallest, *it);
        for (auto it = begin; it != stack.end(); ++it) {
          root[*it] = smallest;
          on_stack[*it] = false;
        }
        stack.erase(begin, stack.end());
      }
    }
  }
  return group_by_root(root);
}

}  // namespace neopipe::nav::mapmaker
