// The map's propagation against a plain reference (spec qrm.md §7 as first written): on random
// 60-100 landmark scenes every fuse must give the same outcome, every relation the same states and
// the map the same number of rolled-back measurements. The library skips the landmarks whose triple
// with a pair is unknown; the reference visits every landmark, so the two are independent.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <random>
#include <utility>
#include <vector>

#include "nav/qrm/composition.hpp"
#include "nav/qrm/edc.hpp"
#include "nav/qrm/operators.hpp"
#include "nav/qrm/relational_map.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

// Spec §7 with every ordered relation in an n^3 cube (pq:r and qp:r = I(pq:r) written together),
// a LIFO queue, and a loop over every landmark d for each of the six orders of a changed triple.
class ReferenceMap {
 public:
  explicit ReferenceMap(int n) : n_(n), cube_(static_cast<std::size_t>(n) * n * n, StateSet::all()) {}

  StateSet relation(int p, int q, int r) const { return cube_[at(p, q, r)]; }
  int inconsistencies() const { return inconsistencies_; }

  FuseOutcome fuse(int a, int b, int c, StateSet states) {
    journal_.clear();
    queue_.clear();
    bool consistent = restrict(a, b, c, states);
    while (consistent && !queue_.empty()) {
      const std::array<int, 3> t = queue_.back();
      queue_.pop_back();
      consistent = process(t[0], t[1], t[2]);
    }
    if (!consistent) {
      for (std::size_t k = journal_.size(); k-- > 0;) cube_[journal_[k].first] = journal_[k].second;
      ++inconsistencies_;
      return FuseOutcome::inconsistent;
    }
    return journal_.empty() ? FuseOutcome::unchanged : FuseOutcome::refined;
  }

 private:
  std::size_t at(int p, int q, int r) const {
    return (static_cast<std::size_t>(p) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(q)) *
               static_cast<std::size_t>(n_) +
           static_cast<std::size_t>(r);
  }

  bool restrict(int a, int b, int c, StateSet states) {
    const StateSet current = relation(a, b, c);
    const StateSet next = current & states;
    if (next == current) return true;
    if (next.empty()) return false;
    journal_.emplace_back(at(a, b, c), current);
    journal_.emplace_back(at(b, a, c), relation(b, a, c));
    cube_[at(a, b, c)] = next;
    cube_[at(b, a, c)] = inverse(next);
    queue_.push_back({a, b, c});
    return true;
  }

  bool process(int a, int b, int c) {
    const StateSet abc = relation(a, b, c);
    if (!restrict(b, c, a, left_shift(abc)) || !restrict(c, a, b, right_shift(abc))) return false;
    const int orders[6][3] = {{a, b, c}, {b, c, a}, {c, a, b}, {b, a, c}, {a, c, b}, {c, b, a}};
    const CompositionTable& comp = composition_table();
    for (const auto& o : orders) {
      const int p = o[0];
      const int q = o[1];
      const int r = o[2];
      const StateSet pqr = relation(p, q, r);
      if (pqr.is_all()) continue;
      for (int d = 0; d < n_; ++d) {
        if (d == p || d == q || d == r) continue;
        const StateSet qrd = relation(q, r, d);
        if (!qrd.is_all() && !restrict(p, q, d, comp(pqr, qrd))) return false;
        const StateSet dpq = relation(d, p, q);
        if (!dpq.is_all() && !restrict(d, p, r, comp(dpq, pqr))) return false;
      }
    }
    return true;
  }

  int n_;
  std::vector<StateSet> cube_;
  int inconsistencies_ = 0;
  std::vector<std::pair<std::size_t, StateSet>> journal_;
  std::vector<std::array<int, 3>> queue_;
};

// What a camera "measures" of a triple: the true state, some of its neighbours, now and then
// nothing ("all") or a wrong state (so that rollbacks happen too).
StateSet synthetic_measurement(std::mt19937_64& rng, State truth) {
  std::uniform_real_distribution<double> u(0, 1);
  const double draw = u(rng);
  if (draw < 0.1) return StateSet::all();
  if (draw < 0.13) {
    std::uniform_int_distribution<State> any(1, kStateCount);
    return StateSet{any(rng)};
  }
  StateSet out{truth};
  for (const State s : adjacent(truth)) {
    if (u(rng) < 0.3) out.insert(s);
  }
  return out;
}

}  // namespace

TEST(QrmMapReference, LargeMapsEqualThePlainPropagation) {
  std::mt19937_64 rng(2121);
  std::uniform_real_distribution<double> coordinate(0, 500);
  std::uniform_int_distribution<int> size(60, 100);
  int inconsistent = 0;
  int refined = 0;
  for (int scene = 0; scene < 3; ++scene) {
    const int n = size(rng);
    std::vector<Eigen::Vector2d> p;
    p.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) p.emplace_back(coordinate(rng), coordinate(rng));
    // Landmarks join in a shuffled order, as a navigator meets them; ids are the point indices.
    std::vector<int> join(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) join[static_cast<std::size_t>(i)] = i;
    std::shuffle(join.begin(), join.end(), rng);
    RelationalMap map;
    ReferenceMap reference(n);
    for (const int id : join) map.add_landmark(static_cast<LandmarkId>(id));
    for (int image = 0; image < 6; ++image) {
      const Eigen::Vector2d camera{coordinate(rng), coordinate(rng)};
      std::vector<int> near(join);
      std::sort(near.begin(), near.end(),
                [&](int x, int y) { return (p[x] - camera).norm() < (p[y] - camera).norm(); });
      near.resize(10);
      for (std::size_t x = 0; x < near.size(); ++x) {
        for (std::size_t y = x + 1; y < near.size(); ++y) {
          for (std::size_t z = y + 1; z < near.size(); ++z) {
            const int a = near[x];
            const int b = near[y];
            const int c = near[z];
            const State truth = classify(p[a], p[b], p[c]);
            if (truth == 0) continue;
            const StateSet measured = synthetic_measurement(rng, truth);
            const FuseOutcome got = map.fuse(a, b, c, measured);
            ASSERT_EQ(got, reference.fuse(a, b, c, measured)) << "scene " << scene << " image " << image;
            inconsistent += got == FuseOutcome::inconsistent ? 1 : 0;
            refined += got == FuseOutcome::refined ? 1 : 0;
          }
        }
      }
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          for (int k = 0; k < n; ++k) {
            if (i == j || j == k || i == k) continue;
            ASSERT_EQ(map.relation(i, j, k), reference.relation(i, j, k))
                << "scene " << scene << " image " << image << ": " << i << ',' << j << ':' << k;
          }
        }
      }
      ASSERT_EQ(map.inconsistencies(), reference.inconsistencies());
    }
  }
  // Both kinds of outcome happened, so both paths (fixpoint and rollback) were compared.
  EXPECT_GT(inconsistent, 20);
  EXPECT_GT(refined, 500);
}
