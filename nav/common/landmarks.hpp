#pragma once
// The description language's landmark descriptors (park-kender.md §3, paper §5.6): the obvious and
// the isolated landmark among the objects in view. The map-maker predicts the navigator's choice
// with exactly these functions, so both link this code.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace neopipe::nav {

/// What a custom-map entry tells the navigator to seek (paper §5.5): the only other object in view
/// (Obvious), the most isolated object in view (Isol), or any object (Any, for the first entry).
/// Far and Near, the objects in view farthest from and nearest to the reference, extend the paper's
/// language (its §8 leaves it open): more than one landmark per view to step to or take a direction
/// from, each rated by how surely the navigator ranks it alike (docs/navigation.md, "Descriptions").
enum class Description : std::uint8_t { Obvious, Isol, Any, Far, Near };

std::string_view description_name(Description d);
std::optional<Description> parse_description(std::string_view text);

/// The objects in view (window or world coordinates: only differences matter) and which of them is
/// the reference, the landmark held at a corner.
struct View {
  std::span<const Eigen::Vector2d> points;
  std::size_t reference = 0;
};

/// True when `p` is preferred to `q` as a landmark seen from `reference` (park-kender.md §3,
/// Decision): farther from the reference, then larger x, then larger y.
bool preferred(const Eigen::Vector2d& reference, const Eigen::Vector2d& p, const Eigen::Vector2d& q);

/// The obvious landmark: the only object in view besides the reference; none otherwise.
std::optional<std::size_t> obvious_landmark(const View& view);

/// c-values of every object in view (paper §5.6.2): the smallest mutual neighbourhood value
/// mnv(A, B) = rank of B among A's neighbours + rank of A among B's (nearest = 1), over B != A.
/// Distance ties inside a ranking go to the preferred object (see `preferred`). An object alone in
/// view has c-value 0.
std::vector<int> c_values(const View& view);

/// The most isolated object in view, the reference excluded: largest c-value, ties to the preferred
/// object. None when nothing but the reference is in view.
std::optional<std::size_t> isolated_landmark(const View& view);

/// The landmark `description` selects in `view`; Any and Far take the preferred object (the
/// farthest), Near the nearest.
std::optional<std::size_t> select_landmark(Description description, const View& view);

/// Every object in view but the reference, in the order `description` prefers them: the first is
/// select_landmark's choice (Obvious, when there is one, ranks the rest by preference like Any; Near
/// ranks nearest first);
/// the next ones are the navigator's second and third candidates when the first leads nowhere.
std::vector<std::size_t> ranked_landmarks(Description description, const View& view);

}  // namespace neopipe::nav
