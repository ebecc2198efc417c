#include "nav/qrm/rng.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "nav/qrm/edc.hpp"

namespace neopipe::nav::qrm {
namespace {

// lcm(1..20): every f_k = a / |S| with |S| <= 20 is a whole multiple of 1 / kLcm.
constexpr std::int64_t kLcm = 232792560;

// sum_k f_k * kLcm, or -1 when some f_k = 1.
std::int64_t scaled_lune_fractions(std::span<const StateSet> relations) {
  std::int64_t sum = 0;
  for (const StateSet s : relations) {
    const int in_lune = (s & kLune).count();
    if (in_lune == s.count()) return -1;
    sum += in_lune * (kLcm / s.count());
  }
  return sum;
}

}  // namespace

std::optional<double> rng_edge_cost(std::span<const StateSet> relations, std::size_t landmarks) {
  const std::int64_t scaled = scaled_lune_fractions(relations);
  if (scaled < 0) return std::nullopt;
  return static_cast<double>(scaled) / (static_cast<double>(landmarks) * static_cast<double>(kLcm));
}

std::optional<RngEdge> rng_edge(const RelationalMap& map, LandmarkId i, LandmarkId j) {
  RngEdge edge{std::min(i, j), std::max(i, j), 0, 0};
  std::vector<StateSet> relations;
  relations.reserve(map.size());
  for (const LandmarkId k : map.landmarks()) {
    if (k != i && k != j) relations.push_back(map.relation(edge.i, edge.j, k));
  }
  edge.scaled_cost = scaled_lune_fractions(relations);
  if (edge.scaled_cost < 0) return std::nullopt;
  const auto unit = static_cast<std::int64_t>(map.size()) * kLcm;
  edge.cost = static_cast<double>(edge.scaled_cost) / static_cast<double>(unit);
  return edge;
}

RngEstimate estimate_rng(const RelationalMap& map) {
  RngEstimate rng;
  rng.unit = static_cast<std::int64_t>(std::max<std::size_t>(map.size(), 1)) * kLcm;
  std::vector<LandmarkId> ids = map.landmarks();
  std::sort(ids.begin(), ids.end());
  for (std::size_t a = 0; a < ids.size(); ++a) {
    for (std::size_t b = a + 1; b < ids.size(); ++b) {
      if (auto edge = rng_edge(map, ids[a], ids[b])) rng.edges.push_back(*edge);
    }
  }
  return rng;
}

DegenerateTripleError::DegenerateTripleError(std::size_t i_, std::size_t j_, std::size_t k_)
    : std::runtime_error("landmarks " + std::to_string(i_) + ", " + std::to_string(j_) + " and " + std::to_string(k_) +
                         " form a degenerate triple (collinear, coincident or on an EDC boundary within 1e-9 of "
                         "the squared distance)"),
      i(i_),
      j(j_),
      k(k_) {}

std::vector<std::pair<std::size_t, std::size_t>> true_rng(std::span<const Eigen::Vector2d> points) {
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      bool edge = true;
      for (std::size_t k = 0; k < n; ++k) {
        if (k == i || k == j) continue;
        const State s = classify(points[i], points[j], points[k]);
        if (s == 0) throw DegenerateTripleError(i, j, k);
        edge = edge && !kLune.contains(s);
      }
      if (edge) edges.emplace_back(i, j);
    }
  }
  return edges;
}

std::vector<std::pair<std::size_t, std::size_t>> rng_by_distances(std::span<const Eigen::Vector2d> points) {
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double dij = (points[i] - points[j]).norm();
      bool edge = true;
      for (std::size_t k = 0; k < n && edge; ++k) {
        if (k == i || k == j) continue;
        edge = std::max((points[i] - points[k]).norm(), (points[j] - points[k]).norm()) >= dij;
      }
      if (edge) edges.emplace_back(i, j);
    }
  }
  return edges;
}

std::vector<LandmarkId> plan_route(const RngEstimate& rng, LandmarkId from, LandmarkId to) {
  std::map<LandmarkId, std::vector<std::pair<LandmarkId, std::int64_t>>> next;
  for (const RngEdge& e : rng.edges) {
    const std::int64_t w = rng.unit + e.scaled_cost;
    next[e.i].emplace_back(e.j, w);
    next[e.j].emplace_back(e.i, w);
  }
  // Labels (cost, path) ordered by cost, then lexicographically by path: extending two labels that
  // end at the same landmark by the same edge keeps their order, so Dijkstra stays exact with it.
  using Label = std::pair<std::int64_t, std::vector<LandmarkId>>;
  std::map<LandmarkId, Label> best;
  std::set<Label> open;
  const Label start{0, {from}};
  best[from] = start;
  open.insert(start);
  std::set<LandmarkId> done;
  while (!open.empty()) {
    const Label label = *open.begin();
    open.erase(open.begin());
    const LandmarkId at = label.second.back();
    if (!done.insert(at).second) continue;
    if (at == to) return label.second;
    const auto it = next.find(at);
    if (it == next.end()) continue;
    for (const auto& [other, w] : it->second) {
      if (done.contains(other)) continue;
      Label candidate{label.first + w, label.second};
      candidate.second.push_back(other);
      const auto known = best.find(other);
      if (known != best.end() && !(candidate < known->second)) continue;
      if (known != best.end()) open.erase(known->second);
      best[other] = candidate;
      open.insert(std::move(candidate));
    }
  }
  return {};
}

}  // namespace neopipe::nav::qrm
