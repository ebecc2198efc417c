#include "nav/mapmaker/planner.hpp"

#include <fmt/format.h>

#include <algorithm>
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
  }
  return path;
}

// Dijkstra with a lexicographic key, (D, U) or (U, D). A pair key with nonnegative increments is as
// good as a scalar one: extending a path never makes its key smaller, and floating-point addition is
// monotone, so the settled key of a node is final and its primary component is the exact minimum.
template <bool kByDistance>
std::optional<PlannedPath> dijkstra(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                    const std::vector<char>& is_target, PlanStats& stats) {
  struct Entry {
    double primary, secondary;
    std::uint32_t node;
  };
  // std::*_heap keep the greatest element first; "later" puts the smallest (key, node id) there.
  const auto later = [](const Entry& a, const Entry& b) {
    return std::tie(a.primary, a.secondary, a.node) > std::tie(b.primary, b.secondary, b.node);
  };
  const std::size_t n = graph.node_count();
  std::vector<double> primary(n, kInf), secondary(n, kInf);
  std::vector<std::uint32_t> pred_edge(n, kNone);
  std::vector<char> settled(n, 0);
  std::vector<Entry> heap;
  for (const std::uint32_t s : sources) {
    if (primary[s] == 0) continue;  // listed twice
    primary[s] = secondary[s] = 0;
    heap.push_back({0, 0, s});
    std::push_heap(heap.begin(), heap.end(), later);
    ++stats.labels_created;
  }
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
      const double p = primary[v] + (kByDistance ? edge.distance : edge.unreliability);
      const double s = secondary[v] + (kByDistance ? edge.unreliability : edge.distance);
      // Strictly better only: equal paths keep the first found, and zero-cost cycles cannot loop.
      if (std::tie(p, s) < std::tie(primary[w], secondary[w])) {
        primary[w] = p;
        secondary[w] = s;
        pred_edge[w] = e;
        heap.push_back({p, s, w});
        std::push_heap(heap.begin(), heap.end(), later);
        ++stats.labels_created;
      }
    }
  }
  return std::nullopt;
}

// The least D and the least U from every node to any target (independently), by Dijkstra on the
// reversed edges; infinity where no target is reachable.
struct RemainingCost {
  std::vector<double> distance, unreliability;
};

std::vector<double> backwards_minimum(const PlanGraph& graph, const std::vector<char>& is_target,
                                      const std::vector<std::uint32_t>& first_in,
                                      const std::vector<std::uint32_t>& in_edges, double PlanEdge::*cost) {
  using Entry = std::pair<double, std::uint32_t>;
  std::vector<double> best(graph.node_count(), kInf);
  std::vector<Entry> heap;
  for (std::uint32_t v = 0; v < graph.node_count(); ++v)
    if (is_target[v]) {
      best[v] = 0;
      heap.emplace_back(0, v);
    }
  const auto later = std::greater<Entry>();
  std::make_heap(heap.begin(), heap.end(), later);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const auto [c, v] = heap.back();
    heap.pop_back();
    if (c > best[v]) continue;
    for (std::uint32_t i = first_in[v]; i < first_in[v + 1]; ++i) {
      const PlanEdge& edge = graph.edges()[in_edges[i]];
      const double through = c + edge.*cost;
      if (through < best[edge.from]) {
        best[edge.from] = through;
        heap.emplace_back(through, edge.from);
        std::push_heap(heap.begin(), heap.end(), later);
      }
    }
  }
  return best;
}

RemainingCost remaining_cost(const PlanGraph& graph, const std::vector<char>& is_target) {
  std::vector<std::uint32_t> first_in(graph.node_count() + 1, 0);
  for (const PlanEdge& e : graph.edges()) ++first_in[e.to + 1];
  for (std::size_t v = 1; v < first_in.size(); ++v) first_in[v] += first_in[v - 1];
  std::vector<std::uint32_t> in_edges(graph.edges().size());
  std::vector<std::uint32_t> cursor(first_in.begin(), first_in.end() - 1);
  for (std::uint32_t i = 0; i < graph.edges().size(); ++i) in_edges[cursor[graph.edges()[i].to]++] = i;
  return {backwards_minimum(graph, is_target, first_in, in_edges, &PlanEdge::distance),
          backwards_minimum(graph, is_target, first_in, in_edges, &PlanEdge::unreliability)};
}

// The compromise min D e^U by bi-criteria label setting over (D, U).
//
// Why Pareto labels suffice: f(D, U) = D e^U is nondecreasing in D (e^U > 0) and in U (D >= 0). If
// path Q dominates path P (D_Q <= D_P, U_Q <= U_P, one strictly) then f(Q) <= f(P), and when f ties
// Q still wins on (D, then U); so the path chosen under (f, D, U) is Pareto-optimal. Along the way,
// a prefix dominated at an intermediate node stays dominated after any common extension (addition is
// monotone, in floating point too), so dropping it loses nothing. Walks with cycles need no
// separate care: a cycle adds nonnegative costs, so the walk is dominated or equalled by the label
// already permanent at the repeated node and is dropped, which also stops zero-cost cycles.
//
// Labels are made permanent in lexicographic (D, U) order (then node id, then creation). A new label
// is never lexicographically before the one it extends, so every permanent label at its node came
// before it: it is dominated by (or equal to) one of them exactly when its U is not below their
// smallest U. That is one number per node; temporary labels are compared one by one.
//
// Pruning: any label whose (f, D, U) is strictly worse than a target label already created cannot
// lead anywhere better, since extending it never decreases f, D or U. And labels come out in D order
// with f >= D, so once D exceeds the best target's f the search is over.
//
// Bounds (what keeps large worlds fast): the bound starts at the better of the min-D and min-U paths
// (both are real paths, so the optimum is no worse), and every completion of a label at node v costs
// at least (D + hD(v)) e^(U + hU(v)), hD and hU being v's exact remaining minima found by Dijkstra
// backwards from the targets. A label whose lower bound exceeds the bound is dropped, and so is a
// label at a node from which no target is reachable. The relative slack covers the rounding of
// adding the remaining minima in another order than a path adds them; a label dropped this way is
// strictly worse than the bound, and so is everything it dominates, so the path chosen is the same
// as without the bounds.
class RatioSearch {
 public:
  RatioSearch(const PlanGraph& graph, const std::vector<char>& is_target, const RemainingCost& remaining,
              const PlannedPath& incumbent, PlanStats& stats)
      : graph_(graph),
        is_target_(is_target),
        remaining_(remaining),
        incumbent_(key_of(incumbent.distance, incumbent.unreliability)),
        stats_(stats),
        min_permanent_u_(graph.node_count(), kInf),
        temporary_head_(graph.node_count(), kNone) {}

  std::optional<PlannedPath> run(std::span<const std::uint32_t> sources) {
    for (const std::uint32_t s : sources) add_label(0, 0, s, kNone, kNone);
    std::uint32_t best = kNone;
    Key best_key{kInf, kInf, kInf};
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const std::uint32_t index = heap_.back().label;
      heap_.pop_back();
      Label& label = labels_[index];
      if (label.state == State::dead) continue;
      if (label.distance > bound_.ratio) break;
      const Key key = key_of(label.distance, label.unreliability);
      if (bound_ < key) {
        label.state = State::dead;
        continue;
      }
      label.state = State::permanent;
      ++stats_.labels_settled;
      min_permanent_u_[label.node] = std::min(min_permanent_u_[label.node], label.unreliability);
      if (is_target_[label.node]) {
        // Extensions of a target label can only tie or lose, so it is not expanded.
        if (key < best_key) {
          best = index;
          best_key = key;
        }
        continue;
      }
      // add_label may grow labels_, so `label` is not used past this point.
      const double d = label.distance, u = label.unreliability;
      for (const std::uint32_t e : graph_.out_edges(label.node)) {
        const PlanEdge& edge = graph_.edges()[e];
        add_label(d + edge.distance, u + edge.unreliability, edge.to, index, e);
      }
    }
    if (best == kNone) return std::nullopt;
    std::vector<std::uint32_t> reversed;
    for (std::uint32_t i = best; labels_[i].edge != kNone; i = labels_[i].pred) reversed.push_back(labels_[i].edge);
    return make_path(graph_, std::move(reversed));
  }

 private:
  enum class State : std::uint8_t { temporary, permanent, dead };
  struct Label {
    double distance, unreliability;
    std::uint32_t node, pred, edge;
    std::uint32_t next_temporary;  ///< the node's list of temporary labels
    State state;
  };
  struct Entry {
    double distance, unreliability;
    std::uint32_t node, label;
  };
  struct Key {
    double ratio, distance, unreliability;
    bool operator<(const Key& o) const {
      return std::tie(ratio, distance, unreliability) < std::tie(o.ratio, o.distance, o.unreliability);
    }
  };

  static bool later(const Entry& a, const Entry& b) {
    return std::tie(a.distance, a.unreliability, a.node, a.label) >
           std::tie(b.distance, b.unreliability, b.node, b.label);
  }
  static Key key_of(double d, double u) { return {ratio_of(d, u), d, u}; }

  void add_label(double d, double u, std::uint32_t node, std::uint32_t pred, std::uint32_t edge) {
    if (u >= min_permanent_u_[node]) return;
    const double rest_d = remaining_.distance[node];
    if (rest_d == kInf) return;  // no target is reachable from here
    const Key& best = bound_.ratio < kInf ? bound_ : incumbent_;
    if (ratio_of(d + rest_d, u + remaining_.unreliability[node]) > best.ratio * (1 + kBoundSlack)) return;
    // Until a target label exists nothing can be pruned, so skip the exp.
    const Key key = bound_.ratio < kInf || is_target_[node] ? key_of(d, u) : Key{kInf, d, u};
    if (bound_ < key) return;
    // Walk the node's temporary labels: drop the new one if one of them dominates or equals it,
    // retire those it dominates, and unlink labels that have since become permanent.
    std::uint32_t* link = &temporary_head_[node];
    while (*link != kNone) {
      Label& other = labels_[*link];
      if (other.state == State::temporary && other.distance <= d && other.unreliability <= u) return;
      if (other.state == State::temporary && !(d <= other.distance && u <= other.unreliability)) {
        link = &other.next_temporary;
        continue;
      }
      if (other.state == State::temporary) other.state = State::dead;
      *link = other.next_temporary;
    }
    if (labels_.size() >= kNone) throw std::length_error("plan_path: more than 2^32 - 1 ratio labels");
    const auto index = static_cast<std::uint32_t>(labels_.size());
    labels_.push_back({d, u, node, pred, edge, temporary_head_[node], State::temporary});
    temporary_head_[node] = index;
    heap_.push_back({d, u, node, index});
    std::push_heap(heap_.begin(), heap_.end(), later);
    ++stats_.labels_created;
    if (is_target_[node] && key < bound_) bound_ = key;
  }

  static constexpr double kBoundSlack = 1e-9;

  const PlanGraph& graph_;
  const std::vector<char>& is_target_;
  const RemainingCost& remaining_;
  const Key incumbent_;  ///< a path known to exist: the optimum is no worse
  PlanStats& stats_;
  std::vector<double> min_permanent_u_;
  std::vector<std::uint32_t> temporary_head_;
  std::vector<Label> labels_;
  std::vector<Entry> heap_;
  Key bound_{kInf, kInf, kInf};  ///< the best target label created so far, permanent or not
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
  }
  return "?";
}

std::optional<CostCriterion> parse_criterion(std::string_view text) {
  for (const CostCriterion c : {CostCriterion::distance, CostCriterion::reliability, CostCriterion::ratio})
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
  edges_.push_back(edge);
  indexed_ = false;
  return static_cast<std::uint32_t>(index);
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
      return dijkstra<true>(graph, sources, is_target, stats);
    case CostCriterion::reliability:
      return dijkstra<false>(graph, sources, is_target, stats);
    case CostCriterion::ratio: {
      // The two Dijkstra paths answer "is there any path" cheaply (the label search would otherwise
      // explore every Pareto label before finding none) and give the label search its first bound.
      const auto shortest = dijkstra<true>(graph, sources, is_target, stats);
      if (!shortest) return std::nullopt;
      const auto most_reliable = dijkstra<false>(graph, sources, is_target, stats);
      const PlannedPath& incumbent = shortest->ratio() <= most_reliable->ratio() ? *shortest : *most_reliable;
      return RatioSearch(graph, is_target, remaining_cost(graph, is_target), incumbent, stats).run(sources);
    }
  }
  return std::nullopt;
}

}  // namespace neopipe::nav::mapmaker
