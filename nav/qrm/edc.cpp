#include "nav/qrm/edc.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace neopipe::nav::qrm {
namespace {

using Signs = std::array<std::int8_t, 6>;

// Spec §2's rows, left state first: e2..e6 are shared by the pair, e1 is + on the left (x < 0 for
// A = (0,0), B = (0,1)) and - on the right.
struct Row {
  State left;
  State right;
  std::array<std::int8_t, 5> e2_to_e6;
  Eigen::Vector2d sample_left;
};

const std::array<Row, 10>& rows() {
  static const std::array<Row, 10> table{{
      {1, 2, {+1, +1, -1, +1, +1}, {-2, 3}},         // beyond B, far from B
      {3, 4, {+1, +1, -1, +1, -1}, {-0.5, 1.5}},     // beyond B, near B
      {5, 10, {+1, -1, -1, +1, +1}, {-2, 0.8}},      // mid, closer to B, far from B
      {6, 9, {+1, -1, -1, +1, -1}, {-0.9, 0.9}},     // mid, closer to B, near B, far from A
      {7, 8, {+1, -1, -1, -1, -1}, {-0.3, 0.7}},     // closer to B, near A (lune)
      {11, 16, {+1, -1, +1, +1, +1}, {-2, 0.2}},     // mid, closer to A, far from A
      {12, 15, {+1, -1, +1, -1, +1}, {-0.9, 0.1}},   // mid, closer to A, near A, far from B
      {13, 14, {+1, -1, +1, -1, -1}, {-0.3, 0.3}},   // closer to A, near B (lune)
      {17, 18, {-1, -1, +1, -1, +1}, {-0.5, -0.5}},  // behind A, near A
      {19, 20, {-1, -1, +1, +1, +1}, {-2, -2}},      // behind A, far from A
  }};
  return table;
}

std::array<Signs, kStateCount + 1> make_signs() {
  std::array<Signs, kStateCount + 1> signs{};
  for (const Row& row : rows()) {
    for (const State s : {row.left, row.right}) {
      signs[s][0] = s == row.left ? 1 : -1;
      for (int i = 0; i < 5; ++i) signs[s][i + 1] = row.e2_to_e6[i];
    }
  }
  return signs;
}

// The list of spec §2, one line per state: the neighbours as ranges.
const std::array<StateSet, kStateCount + 1>& adjacency() {
  static const std::array<StateSet, kStateCount + 1> table{
      StateSet{},
      StateSet::range(2, 6),                                            // 1
      StateSet{1, 3, 4, 9, 10},                                         // 2
      StateSet{1, 2, 4} | StateSet::range(5, 8),                        // 3
      StateSet::range(1, 3) | StateSet::range(7, 10),                   // 4
      StateSet{1, 3, 6, 7} | StateSet::range(11, 13),                   // 5
      StateSet{1, 3, 5, 7} | StateSet::range(11, 13),                   // 6
      StateSet::range(3, 6) | StateSet{8} | StateSet::range(11, 14),    // 7
      StateSet{3, 4, 7, 9, 10} | StateSet::range(13, 16),               // 8
      StateSet{2, 4, 8, 10} | StateSet::range(14, 16),                  // 9
      StateSet{2, 4, 8, 9} | StateSet::range(14, 16),                   // 10
      StateSet::range(5, 7) | StateSet{12, 13, 17, 19},                 // 11
      StateSet::range(5, 7) | StateSet{11, 13, 17, 19},                 // 12
      StateSet::range(5, 8) | StateSet{11, 12, 14, 17, 18},             // 13
      StateSet::range(7, 10) | StateSet{13} | StateSet::range(15, 18),  // 14
      StateSet::range(8, 10) | StateSet{14, 16, 18, 20},                // 15
      StateSet::range(8, 10) | StateSet{14, 15, 18, 20},                // 16
      StateSet::range(11, 14) | StateSet::range(18, 20),                // 17
      StateSet::range(13, 17) | StateSet{19, 20},                       // 18
      StateSet{11, 12, 17, 18, 20},                                     // 19
      StateSet::range(15, 19),                                          // 20
  };
  return table;
}

}  // namespace

std::array<double, 6> edc_values(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a;
  const Eigen::Vector2d ac = c - a;
  const Eigen::Vector2d bc = c - b;
  const double ab2 = ab.squaredNorm();
  const double ac2 = ac.squaredNorm();
  const double bc2 = bc.squaredNorm();
  return {ab.x() * ac.y() - ab.y() * ac.x(), ab.dot(ac), ab.dot(bc), bc2 - ac2, ac2 - ab2, bc2 - ab2};
}

State classify(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const std::array<double, 6> e = edc_values(a, b, c);
  const double tolerance = kDegenerateTolerance * (b - a).squaredNorm();
  for (const double v : e) {
    if (!(std::abs(v) > tolerance)) return 0;  // also NaN
  }
  const bool left = e[0] > 0;
  const bool in_front_of_a = e[1] > 0;
  const bool beyond_b = e[2] > 0;
  const bool closer_to_a = e[3] > 0;
  const bool far_from_a = e[4] > 0;
  const bool far_from_b = e[5] > 0;
  const auto pick = [left](State l, State r) { return left ? l : r; };
  if (beyond_b) return far_from_b ? pick(1, 2) : pick(3, 4);
  if (!in_front_of_a) return far_from_a ? pick(19, 20) : pick(17, 18);
  if (!closer_to_a) {
    if (far_from_b) return pick(5, 10);
    return far_from_a ? pick(6, 9) : pick(7, 8);
  }
  if (far_from_a) return pick(11, 16);
  return far_from_b ? pick(12, 15) : pick(13, 14);
}

const std::array<std::int8_t, 6>& state_signs(State s) {
  static const std::array<Signs, kStateCount + 1> signs = make_signs();
  check_state(s);
  return signs[s];
}

Eigen::Vector2d sample_point(State s) {
  check_state(s);
  for (const Row& row : rows()) {
    if (s == row.left) return row.sample_left;
    if (s == row.right) return {-row.sample_left.x(), row.sample_left.y()};
  }
  return {};  // not reached: every state is in a row
}

State mirror(State s) {
  check_state(s);
  for (const Row& row : rows()) {
    if (s == row.left) return row.right;
    if (s == row.right) return row.left;
  }
  return 0;  // not reached: every state is in a row
}

StateSet adjacent(State s) {
  check_state(s);
  return adjacency()[s];
}

std::optional<std::array<std::size_t, 3>> first_degenerate_triple(std::span<const Eigen::Vector2d> points) {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const std::array<std::array<std::size_t, 3>, 6> orders{
            {{i, j, k}, {j, k, i}, {k, i, j}, {j, i, k}, {k, j, i}, {i, k, j}}};
        for (const auto& [p, q, r] : orders) {
          if (classify(points[p], points[q], points[r]) == 0) return std::array{i, j, k};
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace neopipe::nav::qrm
