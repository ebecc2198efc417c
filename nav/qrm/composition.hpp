#pragma once
// Composition (spec qrm.md §4): comp(s1, s2) is the set of AB:D possible when AB:C = s1 and BC:D = s2.
// The table is computed offline by branch and bound, committed as a text file
// (nav/qrm/composition_table.txt) and compiled into the library, which never reads a file at run time
// unless asked to.

#include <array>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nav/qrm/branch_and_bound.hpp"
#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

/// The branch-and-bound settings of spec §4: box [-8, 8]^4, depth 40.
inline constexpr double kCompositionHalfWidth = 8;
inline constexpr int kCompositionDepth = 40;
/// The format version the library writes and reads.
inline constexpr int kCompositionFormatVersion = 1;

/// A composition table file that cannot be used; the message is one line naming the file and the cause.
class CompositionTableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using CompositionEntries = std::array<std::array<StateSet, kStateCount>, kStateCount>;

/// The 18 strict inequalities of AB:C = s1, BC:D = s2, AB:D = s3 with A = (0,0), B = (0,1) and the
/// unknowns C = (x0, x1), D = (x2, x3).
std::vector<Quadratic> composition_problem(State s1, State s2, State s3);

/// Whether s3 belongs to comp(s1, s2), by branch and bound over [-h, h]^4 to `depth`.
Feasibility composition_feasible(State s1, State s2, State s3, double half_width = kCompositionHalfWidth,
                                 int depth = kCompositionDepth);

/// Every entry by branch and bound (8000 problems); `progress(done, total)` after each (s1, s2).
CompositionEntries generate_composition_entries(const std::function<void(int, int)>& progress = {});

class CompositionTable {
 public:
  explicit CompositionTable(const CompositionEntries& entries);

  /// comp(s1, s2) for states 1..20.
  StateSet operator()(State s1, State s2) const;
  /// comp(X, Y) = union of comp(x, y): at most 20 x 2 look-ups (Y is split into two 10-bit halves,
  /// each pre-composed with every x).
  StateSet operator()(StateSet x, StateSet y) const {
    if (x.empty() || y.empty()) return {};
    const StateSet::Mask y_mask = y.mask();
    const StateSet::Mask lo = (y_mask >> 1) & 0x3FFU;
    const StateSet::Mask hi = (y_mask >> 11) & 0x3FFU;
    StateSet::Mask out = 0;
    for (const State s : x) {
      out |= low_[s - 1][lo] | high_[s - 1][hi];
      if (out == StateSet::kAllMask) break;
    }
    return StateSet::from_mask(out);
  }
  const CompositionEntries& entries() const { return entries_; }
  /// Number of feasible (s1, s2, s3).
  int feasible_triples() const;
  bool operator==(const CompositionTable& o) const { return entries_ == o.entries_; }

 private:
  CompositionEntries entries_;
  std::array<std::array<StateSet::Mask, 1024>, kStateCount> low_{};   ///< comp(x, y) over y in 1..10
  std::array<std::array<StateSet::Mask, 1024>, kStateCount> high_{};  ///< over y in 11..20
};

/// The table compiled into the library (from nav/qrm/composition_table.txt).
const CompositionTable& composition_table();

/// The file format: comment lines, a header naming the format version, box and depth, one line per
/// (s1, s2) in order ("s1 s2 a,b,c"), and a checksum line over those lines.
std::string format_composition_table(const CompositionEntries& entries);
/// Parses `text`; `origin` (a file name) starts every error message.
CompositionEntries parse_composition_table(const std::string& text, const std::string& origin);
/// Reads and parses a table file.
CompositionEntries load_composition_table(const std::string& path);

/// What random configurations say of a table (spec §4's sampling check).
struct SamplingReport {
  std::int64_t samples = 0;
  std::int64_t degenerate = 0;           ///< skipped: some state on a boundary
  std::int64_t outside = 0;              ///< (AB:C, BC:D, AB:D) not in the table: the table is wrong
  int triples_seen = 0;                  ///< distinct feasible triples met
  std::array<State, 3> first_outside{};  ///< the first one outside, if any
};

/// Classifies `samples` random configurations A = (0,0), B = (0,1), C, D and counts the triples the
/// table lacks. C and D are drawn uniform in [-8, 8]^2 or at a log-uniform distance (0.01..10) from
/// A, B or C, so that the thin regions near the segment are met too. Deterministic per seed;
/// `progress(done)` every 2^20 samples.
SamplingReport sample_composition(const CompositionTable& table, std::int64_t samples, std::uint64_t seed,
                                  const std::function<void(std::int64_t)>& progress = {});

/// FNV-1a, 64 bits: the table file's checksum.
std::uint64_t fnv1a64(const std::string& text);

}  // namespace neopipe::nav::qrm
