#include "rig/qrm_metrics.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "nav/qrm/edc.hpp"

namespace neopipe::rig {
namespace {

namespace qrm = nav::qrm;

double percent(double part, double whole) {
  return whole > 0 ? 100 * part / whole : 0;
}

}  // namespace

RngComparison compare_rng(const RngEdges& estimated, const RngEdges& truth) {
  RngEdges a = estimated;
  RngEdges b = truth;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  RngEdges both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
  RngComparison c;
  c.estimated = a.size();
  c.truth = b.size();
  c.common = both.size();
  c.precision = a.empty() ? 1 : static_cast<double>(c.common) / static_cast<double>(a.size());
  c.recall = b.empty() ? 1 : static_cast<double>(c.common) / static_cast<double>(b.size());
  c.equal = a == b;
  return c;
}

QrmMetrics qrm_metrics(const qrm::RelationalMap& map, std::span<const Eigen::Vector2d> truth,
                       const std::optional<RngEdges>& true_rng) {
  for (const qrm::LandmarkId id : map.landmarks()) {
    if (id >= truth.size()) {
      throw std::out_of_range("qrm metrics: landmark " + std::to_string(id) + " is not in the world");
    }
  }
  QrmMetrics m;
  const std::size_t n = truth.size();
  m.landmarks = n;
  m.triples = n < 3 ? 0 : n * (n - 1) * (n - 2) / 6;
  double removed = 0;
  std::size_t resolved = 0;
  std::size_t far_wrong = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const bool known = map.has_landmark(static_cast<qrm::LandmarkId>(i)) &&
                           map.has_landmark(static_cast<qrm::LandmarkId>(j)) &&
                           map.has_landmark(static_cast<qrm::LandmarkId>(k));
        const std::array<std::array<std::size_t, 3>, 3> orders{{{i, j, k}, {j, k, i}, {k, i, j}}};
        bool all_single = true;
        for (const auto& [p, q, r] : orders) {
          const qrm::State s = qrm::classify(truth[p], truth[q], truth[r]);
          if (s == 0) throw qrm::DegenerateTripleError(i, j, k);
          const qrm::StateSet open =
              known ? map.relation(static_cast<qrm::LandmarkId>(p), static_cast<qrm::LandmarkId>(q),
                                   static_cast<qrm::LandmarkId>(r))
                    : qrm::StateSet::all();
          removed += qrm::kStateCount - open.count();
          all_single = all_single && open.count() == 1;
          if (!open.contains(s)) ++m.lost;
          const qrm::StateSet wrong = qrm::StateSet::from_mask(open.mask() & ~qrm::StateSet{s}.mask());
          m.open_wrong += static_cast<std::size_t>(wrong.count());
          far_wrong += static_cast<std::size_t>((wrong & qrm::StateSet::from_mask(~qrm::adjacent(s).mask())).count());
        }
        if (all_single) ++resolved;
      }
    }
  }
  m.m1 = percent(removed, 19.0 * 3.0 * static_cast<double>(m.triples));
  m.m2 = percent(static_cast<double>(resolved), static_cast<double>(m.triples));
  m.m4 = percent(static_cast<double>(far_wrong), static_cast<double>(m.open_wrong));

  const qrm::RngEstimate estimate = qrm::estimate_rng(map);
  for (const qrm::RngEdge& e : estimate.edges) {
    m.m3 += e.cost;
    m.rng.emplace_back(e.i, e.j);
    if (e.scaled_cost == 0) m.certain_rng.emplace_back(e.i, e.j);
  }
  std::sort(m.rng.begin(), m.rng.end());
  std::sort(m.certain_rng.begin(), m.certain_rng.end());
  const RngEdges exact = true_rng ? *true_rng : qrm::true_rng(truth);
  m.versus_truth = compare_rng(m.rng, exact);
  m.certain_versus_truth = compare_rng(m.certain_rng, exact);
  return m;
}

std::optional<std::array<std::size_t, 3>> first_degenerate_triple(std::span<const Eigen::Vector2d> points) {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const std::array<std::array<std::size_t, 3>, 6> orders{
            {{i, j, k}, {j, k, i}, {k, i, j}, {j, i, k}, {k, j, i}, {i, k, j}}};
        for (const auto& [p, q, r] : orders) {
          if (qrm::classify(points[p], points[q], points[r]) == 0) return std::array{i, j, k};
        }
      }
    }
  }
  return std::nullopt;
}

sim::World generate_qrm_world(sim::WorldRequest request) {
  constexpr int kMaxDraws = 1000;
  for (int draw = 0; draw < kMaxDraws; ++draw, ++request.seed) {
    sim::World world = sim::generate_world(request);
    if (!first_degenerate_triple(world.objects)) return world;
  }
  throw sim::WorldError("qrm world: every one of 1000 draws holds a degenerate triple");
}

}  // namespace neopipe::rig
