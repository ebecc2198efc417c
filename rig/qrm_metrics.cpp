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

QrmTruth::QrmTruth(std::span<const Eigen::Vector2d> points) : n_(points.size()) {
  states_.reserve(n_ < 3 ? 0 : n_ * (n_ - 1) * (n_ - 2) / 6);
  for (std::size_t i = 0; i < n_; ++i) {
    for (std::size_t j = i + 1; j < n_; ++j) {
      for (std::size_t k = j + 1; k < n_; ++k) {
        const std::array<qrm::State, 3> s{qrm::classify(points[i], points[j], points[k]),
                                          qrm::classify(points[j], points[k], points[i]),
                                          qrm::classify(points[k], points[i], points[j])};
        if (s[0] == 0 || s[1] == 0 || s[2] == 0) throw qrm::DegenerateTripleError(i, j, k);
        states_.push_back(s);
      }
    }
  }
  rng_ = qrm::true_rng(points);
}

QrmMetrics QrmTruth::metrics(const qrm::RelationalMap& map) const {
  for (const qrm::LandmarkId id : map.landmarks()) {
    if (id >= n_) throw std::out_of_range("qrm metrics: landmark " + std::to_string(id) + " is not in the world");
  }
  QrmMetrics m;
  m.landmarks = n_;
  m.triples = states_.size();
  double removed = 0;
  std::size_t resolved = 0;
  std::size_t far_wrong = 0;
  std::size_t t = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    for (std::size_t j = i + 1; j < n_; ++j) {
      for (std::size_t k = j + 1; k < n_; ++k, ++t) {
        const auto id = [](std::size_t x) { return static_cast<qrm::LandmarkId>(x); };
        const bool known = map.has_landmark(id(i)) && map.has_landmark(id(j)) && map.has_landmark(id(k));
        const std::array<std::array<std::size_t, 3>, 3> orders{{{i, j, k}, {j, k, i}, {k, i, j}}};
        bool all_single = true;
        for (int o = 0; o < 3; ++o) {
          const qrm::State s = states_[t][o];
          const auto& [p, q, r] = orders[o];
          const qrm::StateSet open = known ? map.relation(id(p), id(q), id(r)) : qrm::StateSet::all();
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
  m.versus_truth = compare_rng(m.rng, rng_);
  m.certain_versus_truth = compare_rng(m.certain_rng, rng_);
  return m;
}

QrmMetrics qrm_metrics(const qrm::RelationalMap& map, std::span<const Eigen::Vector2d> truth) {
  return QrmTruth(truth).metrics(map);
}

sim::World generate_qrm_world(sim::WorldRequest request) {
  constexpr int kMaxDraws = 1000;
  for (int draw = 0; draw < kMaxDraws; ++draw, ++request.seed) {
    sim::World world = sim::generate_world(request);
    if (!qrm::first_degenerate_triple(world.objects)) return world;
  }
  throw sim::WorldError("qrm world: every one of 1000 draws holds a degenerate triple");
}

}  // namespace neopipe::rig
