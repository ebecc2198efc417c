#pragma once
// The navigator's view window (park-kender.md §2): a square of side a whose axes are the tool
// frame's (x East, y North). "Landmark L at corner c" places the window so that L sits at c, inset
// by the margin m. The map-maker (world coordinates) and the navigator (window coordinates) both
// reason with these definitions, so they live in the shared library.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace neopipe::nav {

/// The four window corners, in the order of the paper's QOC signature {SE, SW, NE, NW}.
enum class Corner : std::uint8_t { SE = 0, SW = 1, NE = 2, NW = 3 };

inline constexpr std::array<Corner, 4> kCorners{Corner::SE, Corner::SW, Corner::NE, Corner::NW};

constexpr int index(Corner c) {
  return static_cast<int>(c);
}

constexpr std::string_view corner_name(Corner c) {
  constexpr std::array<std::string_view, 4> names{"SE", "SW", "NE", "NW"};
  return names[static_cast<std::size_t>(c)];
}

constexpr std::optional<Corner> parse_corner(std::string_view text) {
  for (const Corner c : kCorners) {
    if (corner_name(c) == text) return c;
  }
  return std::nullopt;
}

/// Which of a landmark's quadrants hold an object, as the map-maker sees them: an extension of the
/// paper's QOC, which only counts them. Two marbles with the same count rarely occupy the same
/// quadrants, so a mistake the count cannot show, the pattern often does. A quadrant whose only
/// objects lie near its window's border (within the map-maker's tolerance) is `unsure`: the survey
/// may have put them on the wrong side. Text: the occupied quadrants, `~` before an unsure one,
/// `none` when all are empty: "2 NE SW ~NW".
enum class Occupancy : std::uint8_t { empty, occupied, unsure };
using QuadrantPattern = std::array<Occupancy, 4>;  ///< indexed by the quadrant's Corner (index())

/// The diagonally opposite corner: holding L at SW looks into L's NE quadrant.
constexpr Corner opposite(Corner c) {
  switch (c) {
    case Corner::SE:
      return Corner::NW;
    case Corner::SW:
      return Corner::NE;
    case Corner::NE:
      return Corner::SW;
    case Corner::NW:
      return Corner::SE;
  }
  return c;
}

constexpr bool is_east(Corner c) {
  return c == Corner::SE || c == Corner::NE;
}
constexpr bool is_north(Corner c) {
  return c == Corner::NE || c == Corner::NW;
}

/// Window side a and corner margin m, in mm (defaults: a = 50, m = 0.05 a).
struct WindowModel {
  double side = 50.0;
  double margin = 2.5;

  static WindowModel with_side(double a) { return {a, 0.05 * a}; }

  /// Lower-left (south-west) corner of the window that holds `landmark` at corner `c`.
  Eigen::Vector2d origin(const Eigen::Vector2d& landmark, Corner c) const {
    return {is_east(c) ? landmark.x() + margin - side : landmark.x() - margin,
            is_north(c) ? landmark.y() + margin - side : landmark.y() - margin};
  }

  /// Where a landmark held at corner c appears in window coordinates (origin at the window's SW
  /// corner): what the navigator's adjust step servoes to.
  Eigen::Vector2d corner_point(Corner c) const {
    return {is_east(c) ? side - margin : margin, is_north(c) ? side - margin : margin};
  }

  /// Strictly inside the window whose SW corner is `window_origin` (park-kender.md §2: visible).
  bool sees(const Eigen::Vector2d& window_origin, const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = p - window_origin;
    return q.x() > 0 && q.x() < side && q.y() > 0 && q.y() < side;
  }

  /// Two objects fit in one window (the general parkway's edge, park-kender.md §3).
  bool fit_together(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const {
    const double reach = side - 2 * margin;
    return std::abs(p.x() - q.x()) < reach && std::abs(p.y() - q.y()) < reach;
  }
};

}  // namespace neopipe::nav
