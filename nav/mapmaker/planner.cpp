#include "nav/mapmaker/planner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace neopipe::nav::mapmaker {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kInf = std::numeric_limits<double>::infinity();

// D = 0 makes the ratio 0 whatever U is; without the special case a huge U gives 0 * inf = NaN, which
// would break every comparison below.
double ratio_of(double distance, double unreliability) {
  return distance == 0 ? 0.0 : distance * std::exp(unreliability);
}

void check_cost(std::size_t index, const PlanEdge& edge, const char* what, double value) {
  if (!std::isfinite(value) || value < 0)
    throw std::invalid_argument(fmt::format("plan edge {} ({} -> {}): {} {} is not a finite number >= 0", index,
                                            edge.from, edge.to, what, value));
}

std::vector<char> node_mask(std::span<const std::uint32_t> nodes, std::size_t node_count, const char* what) {
  std::vector<char> mask(node_count, 0);
  for (const std::uint32_t node : nodes) {
    if (node >= node_count)
      throw std::invalid_argument(
          fmt::format("plan_path: {} node {} is out of range ({} nodes)", what, node, node_count));
    mask[node] = 1;
  }
  return mask;
}

// `reversed` is the path from target back to source. The sums are added source to target, the order
// in which the searches accumulated them, so they equal the search's costs bit for bit.
PlannedPath make_path(const PlanGraph& graph, std::vector<std::uint32_t> reversed) {
  std::reverse(reversed.begin(), reversed.end());
  PlannedPath path{std::move(reversed)};
  for (const std::uint32_t e : path.edges) {
    path.distance += graph.edges()[e].distance;
    path.unreliability += graph.edges()[e].unreliability;
    path.landmark_distance += graph.edges()[e].landmark_distance;
  }
  return path;
}

// wd D + wu U + wl L of an edge. A zero weight adds an exact 0, so a form with one unit weight gives
// that cost bit for bit, and sums along a path equal make_path's.
struct Form {
  double wd = 0, wu = 0, wl = 0;
  double of(const PlanEdge& e) const { return wd * e.distance + wu * e.unreliability + wl * e.landmark_distance; }
};

// What a Dijkstra run minimises: (first, then second, then third). Each criterion's tie-breaks are
// part of its order, so no criterion needs a search of its own.
struct Order {
  Form first, second, third;
  static Order distance() { return {{1, 0, 0}, {0, 1, 0}, {}}; }
  static Order reliability() { return {{0, 1, 0}, {1, 0, 0}, {}}; }
  static Order landmark() { return {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}; }
  // The compromise's weighted sums, ties to the shorter.
  static Order weighted(const Form& line) { return {line, {1, 0, 0}, {}}; }
};

using Key = std::array<double, 3>;

Key extend(const Key& from, const Order& order, const PlanEdge& edge) {
  return {from[0] + order.first.of(edge), from[1] + order.second.of(edge), from[2] + order.third.of(edge)};
}

// Dijkstra with a lexicographic key. A tuple key with nonnegative increments is as good as a scalar
// one: extending a path never makes its key smaller, and floating-point addition is monotone, so the
// settled key of a node is final and its first component is the exact minimum.
std::optional<PlannedPath> dijkstra(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                    const std::vector<char>& is_target, const Order& order, PlanStats& stats) {
  struct Entry {
    Key key;
    std::uint32_t node;
  };
  // std::*_heap keep the greatest element first; "later" puts the smallest (key, node id) there.
  const auto later = [](const Entry& a, const Entry& b) {
    return std::tie(a.key[0], a.key[1], a.key[2], a.node) > std::tie(b.key[0], b.key[1], b.key[2], b.node);
  };
  const std::size_t n = graph.node_count();
  std::vector<Key> key(n, Key{kInf, kInf, kInf});
  std::vector<std::uint32_t> pred_edge(n, kNone);
  std::vector<char> settled(n, 0);
  std::vector<Entry> heap;
  for (const std::uint32_t s : sources) {
    if (key[s][0] == 0) continue;  // listed twice
    key[s] = Key{0, 0, 0};
    heap.push_back({key[s], s});
    std::push_heap(heap.begin(), heap.end(), later);
    ++stats.labels_created;
  }
  ++stats.searches;
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const std::uint32_t v = heap.back().node;
    heap.pop_back();
    if (settled[v]) continue;  // a stale entry: v was improved and settled by a smaller key
    settled[v] = 1;
    ++stats.labels_settled;
    if (is_target[v]) {
      std::vector<std::uint32_t> reversed;
      for (std::uint32_t node = v; pred_edge[node] != kNone; node = graph.edges()[pred_edge[node]].from)
        reversed.push_back(pred_edge[node]);
      return make_path(graph, std::move(reversed));
    }
    for (const std::uint32_t e : graph.out_edges(v)) {
      const PlanEdge& edge = graph.edges()[e];
      const std::uint32_t w = edge.to;
      if (settled[w]) continue;
      const Key k = extend(key[v], order, edge);
      // Strictly better only: equal paths keep the first found, and zero-cost cycles cannot loop.
      if (std::tie(k[0], k[1], k[2]) < std::tie(key[w][0], key[w][1], key[w][2])) {
        key[w] = k;
        pred_edge[w] = e;
        heap.push_back({k, w});
        std::push_heap(heap.begin(), heap.end(), later);
        ++stats.labels_created;
      }
    }
  }
  return std::nullopt;
}

// The compromise min f = D e^U. log f = log D + U is concave in (D, U), and a concave function takes
// its minimum over the convex hull of the paths' (D, U) points at a vertex of that hull; as f grows
// with D and with U, at a vertex of its lower-left chain. Those vertices are exactly the paths that
// minimise wd D + wu U for some weights wd, wu >= 0, so a few Dijkstra runs find them all: between
// two known vertices P (less D) and Q (less U) the weights normal to PQ either find a path below
// the segment, a new vertex to split at, or prove there is none (Aneja & Nair's dichotomic search);
// a segment is skipped when no point between its ends could beat the best path found so far.
// The result is the exact minimum up to rounding: a vertex within rounding of a segment cannot beat
// the segment's ends by more than that, f being concave along it.
class CompromiseSearch {
 public:
  CompromiseSearch(const PlanGraph& graph, std::span<const std::uint32_t> sources, const std::vector<char>& is_target,
                   PlanStats& stats)
      : graph_(graph), sources_(sources), is_target_(is_target), stats_(stats) {}

  std::optional<PlannedPath> run() {
    const auto shortest = dijkstra(graph_, sources_, is_target_, Order::distance(), stats_);
    if (!shortest) return std::nullopt;
    const auto most_reliable = dijkstra(graph_, sources_, is_target_, Order::reliability(), stats_);
    best_ = *shortest;
    consider(*most_reliable);
    split({*shortest, Order::distance().first}, {*most_reliable, Order::reliability().first}, 0);
    return best_;
  }

 private:
  static constexpr int kMaxDepth = 60;           // hull vertices are few; this only guards rounding
  static constexpr double kRelativeGap = 1e-12;  // a path must lie this far below the segment

  // (D + offset) e^U: with an offset > 0 a route the navigator travels 0 mm for (its goal in view)
  // is not free whatever its U (PlanGraph::set_ratio_offset).
  double cost(double distance, double unreliability) const {
    return ratio_of(distance + graph_.ratio_offset(), unreliability);
  }
  double cost(const PlannedPath& p) const { return cost(p.distance, p.unreliability); }
  bool better(const PlannedPath& a, const PlannedPath& b) const {
    return std::make_tuple(cost(a), a.distance, a.unreliability) <
           std::make_tuple(cost(b), b.distance, b.unreliability);
  }
  void consider(const PlannedPath& p) {
    if (better(p, best_)) best_ = p;
  }

  // A hull vertex and the weights it minimises: every path lies on or above its line wd D + wu U = c.
  struct Vertex {
    PlannedPath path;
    Form line;
    double level() const { return line.wd * path.distance + line.wu * path.unreliability; }
  };

  // Every path between p and q lies in the triangle under the segment pq and above both lines; f is
  // concave, so its least value there is at a corner: p, q (already considered) or where the lines
  // cross.
  double floor_between(const Vertex& p, const Vertex& q) const {
    const double det = p.line.wd * q.line.wu - p.line.wu * q.line.wd;
    double d = p.path.distance;
    double u = q.path.unreliability;
    if (det > 0) {
      d = std::max(d, (p.level() * q.line.wu - p.line.wu * q.level()) / det);
      u = std::max(u, (p.line.wd * q.level() - p.level() * q.line.wd) / det);
    }
    return cost(d, u);
  }

  // p: the vertex with less D, q: the one with less U. Segments whose floor is above the best f
  // found so far cannot hold the optimum: on a long route most of the hull is never computed.
  void split(const Vertex& p, const Vertex& q, int depth) {
    if (depth > kMaxDepth || !(p.path.distance < q.path.distance && q.path.unreliability < p.path.unreliability)) {
      return;
    }
    if (floor_between(p, q) > cost(best_) * (1 + kRelativeGap)) return;
    const Form w{p.path.unreliability - q.path.unreliability, q.path.distance - p.path.distance};
    const auto r = dijkstra(graph_, sources_, is_target_, Order::weighted(w), stats_);
    const Vertex v{*r, w};
    const double on_segment = w.wd * p.path.distance + w.wu * p.path.unreliability;
    if (!(v.level() < on_segment - kRelativeGap * on_segment)) return;
    if (!(p.path.distance < r->distance && r->distance < q.path.distance)) return;
    consider(*r);
    // The side with the lower floor first: a better best prunes more of the other.
    if (floor_between(p, v) <= floor_between(v, q)) {
      split(p, v, depth + 1);
      split(v, q, depth + 1);
    } else {
      split(v, q, depth + 1);
      split(p, v, depth + 1);
    }
  }

  const PlanGraph& graph_;
  std::span<const std::uint32_t> sources_;
  const std::vector<char>& is_target_;
  PlanStats& stats_;
  PlannedPath best_;
};

}  // namespace

std::string_view criterion_name(CostCriterion c) {
  switch (c) {
    case CostCriterion::distance:
      return "distance";
    case CostCriterion::reliability:
      return "reliability";
    case CostCriterion::ratio:
      return "ratio";
    case CostCriterion::landmark:
      return "landmark";
  }
  return "?";
}

std::optional<CostCriterion> parse_criterion(std::string_view text) {
  for (const CostCriterion c : kCriteria)
    if (text == criterion_name(c)) return c;
  return std::nullopt;
}

PlanGraph::PlanGraph(std::size_t nodes) {
  // Ids are 32-bit and kNone is reserved, so the largest id must stay below it.
  if (nodes > kNone) throw std::length_error(fmt::format("PlanGraph: {} nodes do not fit 32-bit ids", nodes));
  first_out_.assign(nodes + 1, 0);
}

std::uint32_t PlanGraph::add_edge(const PlanEdge& edge) {
  const std::size_t index = edges_.size();
  if (index >= kNone) throw std::length_error("PlanGraph: more than 2^32 - 1 edges");
  if (edge.from >= node_count() || edge.to >= node_count())
    throw std::invalid_argument(
        fmt::format("plan edge {} ({} -> {}): node out of range ({} nodes)", index, edge.from, edge.to, node_count()));
  check_cost(index, edge, "distance", edge.distance);
  check_cost(index, edge, "unreliability", edge.unreliability);
  check_cost(index, edge, "landmark distance", edge.landmark_distance);
  edges_.push_back(edge);
  indexed_ = false;
  return static_cast<std::uint32_t>(index);
}

void PlanGraph::set_ratio_offset(double offset) {
  if (!std::isfinite(offset) || offset < 0)
    throw std::invalid_argument(fmt::format("ratio offset {}: must be a finite number >= 0", offset));
  ratio_offset_ = offset;
}

std::span<const std::uint32_t> PlanGraph::out_edges(std::uint32_t node) const {
  if (!indexed_) index();
  return {out_.data() + first_out_[node], out_.data() + first_out_[node + 1]};
}

// A stable counting sort by source node, which keeps each node's edges in insertion order.
void PlanGraph::index() const {
  std::fill(first_out_.begin(), first_out_.end(), 0);
  for (const PlanEdge& e : edges_) ++first_out_[e.from + 1];
  for (std::size_t v = 1; v < first_out_.size(); ++v) first_out_[v] += first_out_[v - 1];
  out_.resize(edges_.size());
  std::vector<std::uint32_t> cursor(first_out_.begin(), first_out_.end() - 1);
  for (std::uint32_t i = 0; i < edges_.size(); ++i) out_[cursor[edges_[i].from]++] = i;
  indexed_ = true;
}

double PlannedPath::ratio() const {
  return ratio_of(distance, unreliability);
}

std::optional<PlannedPath> plan_path(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                     std::span<const std::uint32_t> targets, CostCriterion criterion) {
  PlanStats stats;
  return plan_path(graph, sources, targets, criterion, stats);
}

std::optional<PlannedPath> plan_path(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                     std::span<const std::uint32_t> targets, CostCriterion criterion,
                                     PlanStats& stats) {
  stats = {};
  const std::vector<char> is_source = node_mask(sources, graph.node_count(), "source");
  const std::vector<char> is_target = node_mask(targets, graph.node_count(), "target");
  // Checked up front rather than left to the search: a zero-cost path from another source to a
  // target with a smaller id would otherwise tie with, and beat, the empty path.
  for (std::size_t v = 0; v < graph.node_count(); ++v)
    if (is_source[v] && is_target[v]) return PlannedPath{};
  switch (criterion) {
    case CostCriterion::distance:
      return dijkstra(graph, sources, is_target, Order::distance(), stats);
    case CostCriterion::reliability:
      return dijkstra(graph, sources, is_target, Order::reliability(), stats);
    case CostCriterion::landmark:
      return dijkstra(graph, sources, is_target, Order::landmark(), stats);
    case CostCriterion::ratio:
      return CompromiseSearch(graph, sources, is_target, stats).run();
  }
  return std::nullopt;
}

}  // namespace neopipe::nav::mapmaker
