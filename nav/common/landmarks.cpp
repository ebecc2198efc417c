#include "nav/common/landmarks.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

namespace neopipe::nav {

std::string_view description_name(Description d) {
  constexpr std::array<std::string_view, 5> names{"Obvious", "Isol", "*", "Far", "Near"};
  return names[static_cast<std::size_t>(d)];
}

std::optional<Description> parse_description(std::string_view text) {
  for (const Description d :
       {Description::Obvious, Description::Isol, Description::Any, Description::Far, Description::Near}) {
    if (description_name(d) == text) return d;
  }
  return std::nullopt;
}

bool preferred(const Eigen::Vector2d& reference, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const double dp = (p - reference).squaredNorm();
  const double dq = (q - reference).squaredNorm();
  if (dp != dq) return dp > dq;
  if (p.x() != q.x()) return p.x() > q.x();
  return p.y() > q.y();
}

std::optional<std::size_t> obvious_landmark(const View& view) {
  if (view.points.size() != 2) return std::nullopt;
  return view.reference == 0 ? 1 : 0;
}

std::vector<int> c_values(const View& view) {
  const std::size_t n = view.points.size();
  const Eigen::Vector2d& ref = view.points[view.reference];
  // rank[a * n + b]: rank of b among a's neighbours (1 = nearest).
  std::vector<int> rank(n * n, 0);
  std::vector<std::size_t> order(n);
  for (std::size_t a = 0; a < n; ++a) {
    order.resize(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(a));
    const Eigen::Vector2d& pa = view.points[a];
    std::sort(order.begin(), order.end(), [&](std::size_t b, std::size_t c) {
      const double db = (view.points[b] - pa).squaredNorm();
      const double dc = (view.points[c] - pa).squaredNorm();
      if (db != dc) return db < dc;
      return preferred(ref, view.points[b], view.points[c]);
    });
    for (std::size_t r = 0; r < order.size(); ++r) rank[a * n + order[r]] = static_cast<int>(r) + 1;
  }
  std::vector<int> c(n, 0);
  for (std::size_t a = 0; a < n; ++a) {
    int smallest = std::numeric_limits<int>::max();
    for (std::size_t b = 0; b < n; ++b) {
      if (b != a) smallest = std::min(smallest, rank[a * n + b] + rank[b * n + a]);
    }
    c[a] = n > 1 ? smallest : 0;
  }
  return c;
}

std::optional<std::size_t> isolated_landmark(const View& view) {
  if (view.points.size() < 2) return std::nullopt;
  if (view.points.size() == 2) return obvious_landmark(view);
  const std::vector<int> c = c_values(view);
  const Eigen::Vector2d& ref = view.points[view.reference];
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < view.points.size(); ++i) {
    if (i == view.reference) continue;
    if (!best || c[i] > c[*best] || (c[i] == c[*best] && preferred(ref, view.points[i], view.points[*best]))) best = i;
  }
  return best;
}

namespace {

// Near's order: nearer to the reference first; exact ties as `preferred` breaks them past distance.
bool nearer(const Eigen::Vector2d& reference, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const double dp = (p - reference).squaredNorm();
  const double dq = (q - reference).squaredNorm();
  if (dp != dq) return dp < dq;
  if (p.x() != q.x()) return p.x() > q.x();
  return p.y() > q.y();
}

}  // namespace

std::optional<std::size_t> select_landmark(Description description, const View& view) {
  if (description == Description::Obvious) return obvious_landmark(view);
  if (description == Description::Isol) return isolated_landmark(view);
  const std::vector<std::size_t> ranked = ranked_landmarks(description, view);
  return ranked.empty() ? std::nullopt : std::optional<std::size_t>(ranked.front());
}

std::vector<std::size_t> ranked_landmarks(Description description, const View& view) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < view.points.size(); ++i)
    if (i != view.reference) order.push_back(i);
  const Eigen::Vector2d& ref = view.points[view.reference];
  const auto by_preference = [&](std::size_t p, std::size_t q) {
    return preferred(ref, view.points[p], view.points[q]);
  };
  if (description == Description::Isol && view.points.size() > 2) {
    const std::vector<int> c = c_values(view);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t p, std::size_t q) { return c[p] != c[q] ? c[p] > c[q] : by_preference(p, q); });
  } else if (description == Description::Near) {
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t p, std::size_t q) { return nearer(ref, view.points[p], view.points[q]); });
  } else {
    std::stable_sort(order.begin(), order.end(), by_preference);
  }
  return order;
}

}  // namespace neopipe::nav
