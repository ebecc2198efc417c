#pragma once
// The custom map (park-kender.md §8, paper §5.5 and §6.3.4): the only thing the map-maker sends the
// navigator. An entry (D, [T], [E...], M): seek the landmark described by D; optionally slide along
// the reference->landmark direction (Trajp) or back (Trajn) until a new object enters and take that
// one; verify it by its QOC and apply the recovery rules E; adjust it to corner M ('-' at the goal).
// Text form, as in the paper: ((*, SW), (Isol, SE), (Isol, Trajp, (2, NW, Isol), (1, -), -)), with
// four extensions: a slide's bound ("Trajp:120", mm), where its goal should enter ("@85/-3~8/12",
// SlideGoal), a QOC to measure only in doubt ("(1, ?)"), and which quadrants the verified QOC counts
// ("(2 NE SW ~NW, -)", see QuadrantPattern).

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "nav/common/landmarks.hpp"
#include "nav/common/window.hpp"

namespace neopipe::nav {

enum class Direction : std::uint8_t { positive, negative };  // Trajp, Trajn

constexpr std::string_view direction_name(Direction d) {
  return d == Direction::positive ? "p" : "n";
}
constexpr std::string_view trajectory_name(Direction d) {
  return d == Direction::positive ? "Trajp" : "Trajn";
}

/// (k, corner, D'): when the landmark reached has QOC k, hold it at `corner` and seek D' (which
/// leads back toward the intended landmark). (k, -): QOC k is the intended landmark's: verified.
/// (k, ?): QOC k is the intended landmark's, but nothing else could have been taken for it: the
/// navigator measures it only when the view made it guess (seek.cpp).
struct RecoveryRule {
  int qoc = 0;
  std::optional<Corner> corner;  ///< none: "verified / arrived"
  Description seek = Description::Isol;
  bool only_in_doubt = false;  ///< (k, ?): with no corner
  /// With no corner: the quadrants QOC k counts, when the map gives them.
  std::optional<QuadrantPattern> quadrants;

  /// (k, -), or (k, ?) when `only_in_doubt`.
  static RecoveryRule verified(int qoc, bool only_in_doubt = false) {
    RecoveryRule r;
    r.qoc = qoc;
    r.only_in_doubt = only_in_doubt;
    return r;
  }
  /// (k, corner, D').
  static RecoveryRule leading_back(int qoc, Corner corner, Description seek) {
    RecoveryRule r;
    r.qoc = qoc;
    r.corner = corner;
    r.seek = seek;
    return r;
  }
  friend bool operator==(const RecoveryRule&, const RecoveryRule&) = default;
};

/// Where a slide's goal lies from the reference, in the track's axes: mm along the slide and across
/// it (positive to the left of the direction of travel), and how far from there the navigator may
/// find it given the map-maker's errors. A newcomer entering elsewhere is not the goal: one before
/// it is passed by, one after it says the goal went by beside the window. Whole mm, as written.
struct SlideGoal {
  double along = 0;
  double cross = 0;
  double along_tolerance = 0;
  double cross_tolerance = 0;
  friend bool operator==(const SlideGoal&, const SlideGoal&) = default;

  /// Whether an object at `along`, `cross` (track axes, from the reference) may be the goal.
  bool admits(double at_along, double at_cross) const {
    return std::abs(at_along - along) <= along_tolerance && std::abs(at_cross - cross) <= cross_tolerance;
  }
  /// Whether the goal must have entered before an object at `at_along` did.
  bool passed(double at_along) const { return at_along > along + along_tolerance; }
};

struct MapEntry {
  Description seek = Description::Isol;
  std::optional<Direction> slide;
  std::vector<RecoveryRule> rules;
  std::optional<Corner> adjust;  ///< none ('-'): the goal, stay
  /// mm: how far the slide may go before the navigator concludes its landmark will not enter
  /// (written "Trajp:120"): the map-maker's slide plus what its errors allow. None: no bound.
  std::optional<double> slide_limit;
  /// Where the slide's goal should enter (written "Trajp:120@85/-3~8/12"). None: any newcomer may be.
  std::optional<SlideGoal> slide_goal;
  friend bool operator==(const MapEntry&, const MapEntry&) = default;

  /// The QOC that verifies this entry's landmark, when the map gives one.
  std::optional<int> verified_qoc() const;
  /// The quadrants that QOC counts, when the map gives them.
  std::optional<QuadrantPattern> verified_quadrants() const;
  /// The map gives the QOC only for when the navigator is in doubt: (k, ?).
  bool verify_only_in_doubt() const;
  /// The rule for a landmark reached with QOC k that is not the verified one.
  const RecoveryRule* recovery_for(int qoc) const;
};

struct CustomMap {
  std::vector<MapEntry> entries;
  friend bool operator==(const CustomMap&, const CustomMap&) = default;
};

class CustomMapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "NE SW ~NW" (the occupied quadrants, ~ before an unsure one), "none" when all are empty.
std::string format_quadrants(const QuadrantPattern& pattern);
/// Whether a QOC of k can count these quadrants: at least the occupied ones, at most those and the
/// unsure ones.
bool quadrants_allow(const QuadrantPattern& pattern, int qoc);
std::string format_entry(const MapEntry& entry);
/// The whole map on one line, entries in order.
std::string format_custom_map(const CustomMap& map);
/// Reads the text form back; throws CustomMapError naming the character offset and what was
/// expected. parse(format(m)) == m.
CustomMap parse_custom_map(std::string_view text);

}  // namespace neopipe::nav
