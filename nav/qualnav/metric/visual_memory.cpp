#include "nav/qualnav/metric/visual_memory.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <tuple>

namespace neopipe::nav::qualnav {

std::size_t VisualMemory::add_viewpath(const std::vector<Viewframe>& viewframes) {
  const std::size_t path = viewpaths_++;
  const std::size_t first = nodes_.size();
  for (std::size_t i = 0; i < viewframes.size(); ++i) {
    nodes_.push_back({path, i, viewframes[i]});
    links_.emplace_back();
    scales_.add(viewframes[i]);
  }
  const auto link = [&](std::size_t a, std::size_t b, double cost) {
    links_[a].push_back({b, cost});
    links_[b].push_back({a, cost});
  };
  for (std::size_t n = first + 1; n < nodes_.size(); ++n) {
    const auto h = viewframe_heading(nodes_[n - 1].view, nodes_[n].view, scales_, options_);
    // Consecutive viewframes are linked whatever the estimate; the spacing is the fallback cost.
    link(n - 1, n, h ? h->distance : kViewpathSpacingMm);
  }
  for (std::size_t n = first; n < nodes_.size(); ++n) {
    for (std::size_t m = 0; m < first; ++m) {
      if (shared_landmarks(nodes_[n].view, nodes_[m].view).size() < 2) continue;
      const auto h = viewframe_heading(nodes_[n].view, nodes_[m].view, scales_, options_);
      if (h && h->distance <= kLinkDistanceMm) link(n, m, h->distance);
    }
  }
  return path;
}

std::vector<std::size_t> astar(const std::vector<std::vector<MemoryLink>>& graph, std::size_t start, std::size_t goal,
                               const std::function<double(std::size_t)>& heuristic) {
  const std::size_t n = graph.size();
  if (start >= n || goal >= n) return {};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, kInf);
  std::vector<std::size_t> parent(n, n);
  std::vector<bool> closed(n, false);
  using Entry = std::tuple<double, std::size_t>;  // f, node: ties by lower id
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  g[start] = 0;
  open.emplace(heuristic(start), start);
  while (!open.empty()) {
    const auto [f, u] = open.top();
    open.pop();
    if (closed[u]) continue;
    closed[u] = true;
    if (u == goal) break;
    for (const MemoryLink& e : graph[u]) {
      if (closed[e.to] || g[u] + e.cost >= g[e.to]) continue;
      g[e.to] = g[u] + e.cost;
      parent[e.to] = u;
      open.emplace(g[e.to] + heuristic(e.to), e.to);
    }
  }
  if (!closed[goal]) return {};
  std::vector<std::size_t> path;
  for (std::size_t v = goal; v != n; v = parent[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<std::size_t> plan_over_memory(const VisualMemory& memory, std::size_t start, std::size_t goal) {
  const auto& nodes = memory.nodes();
  const auto heuristic = [&](std::size_t v) {
    if (goal >= nodes.size() || v == goal) return 0.0;
    const auto h = viewframe_heading(nodes[v].view, nodes[goal].view, memory.scales(), memory.localization());
    return h ? h->distance : 0.0;
  };
  return astar(memory.links(), start, goal, heuristic);
}

double path_cost(const std::vector<std::vector<MemoryLink>>& graph, const std::vector<std::size_t>& path) {
  double total = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const auto& out = graph[path[i - 1]];
    const auto it = std::find_if(out.begin(), out.end(), [&](const MemoryLink& e) { return e.to == path[i]; });
    if (it == out.end()) return std::numeric_limits<double>::infinity();
    total += it->cost;
  }
  return total;
}

}  // namespace neopipe::nav::qualnav
