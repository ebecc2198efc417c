#include "calib/dot_grid.hpp"

// How the dots are ordered, and why this way.
//
// 1. Area: blobs whose area is far from the median (more than kAreaRatio either way) are strays;
//    with at most a few strays the median is a dot's area. The band is wide because perspective
//    makes near dots larger than far ones.
// 2. Lattice growth, like findCirclesGrid's neighbour graph but with a projective model: from a seed
//    dot and its two nearest non-parallel neighbours (a lattice basis, though not necessarily the
//    grid's own axes: under strong foreshortening a diagonal can be shorter than an axis), cells
//    of the integer lattice are assigned dots ring by ring. Each unassigned cell next to assigned
//    ones is predicted by the map fitted to all assigned cells (affine at first, a homography once
//    there are enough), corrected by the residuals of its assigned neighbours so that lens
//    distortion does not accumulate across a large grid, and takes the nearest free dot within
//    kSnap of the local spacing. The lattice cannot then jump a row, and strays off the lattice are
//    never taken. Unlike a convex-hull start, no stray has to be guessed away first. Once nothing
//    more is taken, the map is refitted to every cell and each cell re-snapped to the dot nearest
//    its neighbours' prediction, undoing any stray an early, rougher prediction let in.
// 3. The grid's axes: the assigned cells are the dots plus any stray that happens to sit on the
//    lattice's extension. The grid is the one cols x rows window, in some basis of the lattice with
//    small coefficients, whose every cell holds a dot; a sheared window never fits inside the
//    rectangle, and a second full window would need a whole row of strays, which is reported as
//    ambiguous rather than guessed.
// 4. Labelling: of the grid's symmetries that keep its shape, those with cross(col_dir, row_dir) < 0
//    (rotations of the target seen from the front), the one with col_dir most nearly along +u. An
//    axis is the mean first-to-last span of the rows (columns), a direction that perspective does
//    not make depend on where in the grid it is taken. At a tie (col_dir perpendicular to +u, or at
//    45 degrees to it for a square grid) the dots' noise decides.

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "calib/cross2.hpp"
#include "calib/homography.hpp"

namespace neopipe::calib {
namespace {

using Vec2 = Eigen::Vector2d;
using Cell = std::pair<int, int>;  // lattice coordinates

// Dots of one target differ less than this from the median area.
constexpr double kAreaRatio = 3.0;
// Fraction of the local spacing a dot may lie from its prediction: under half, so that a dot is
// never taken for a neighbouring cell's, with room for noise and what the map does not follow.
constexpr double kSnap = 0.3;
// sin 15 degrees: a second neighbour closer than that in angle to the first is parallel to it.
constexpr double kMinSinBasis = 0.26;
// Enough neighbours of a seed to find a non-parallel one among a few strays.
constexpr int kSeedNeighbours = 8;
// Bounds the work on images full of blobs but no grid; with a few strays the first seed or two do.
constexpr std::size_t kMaxSeeds = 200;
// Below this many cells an affine map: a small patch pins perspective down worse than noise does.
constexpr int kHomographyCells = 10;
// The grid's axes in a reduced lattice basis have small coefficients, even foreshortened 2:1.
constexpr int kMaxBasisCoefficient = 3;
// Each re-snap pass settles what the one before freed; one usually changes nothing.
constexpr int kResnapPasses = 3;

constexpr std::array<Cell, 8> kNeighbours{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}}};

Vec2 as_vec(const Cell& c) {
  return {c.first, c.second};
}

// Similarity taking points to centroid 0 and mean distance sqrt 2 (Hartley's normalisation).
Eigen::Matrix3d normaliser(const std::vector<Vec2>& p) {
  Vec2 mean = Vec2::Zero();
  for (const auto& x : p) mean += x;
  mean /= static_cast<double>(p.size());
  double spread = 0;
  for (const auto& x : p) spread += (x - mean).norm();
  spread /= static_cast<double>(p.size());
  const double s = spread > 0 ? std::sqrt(2.0) / spread : 1.0;
  Eigen::Matrix3d t;
  t << s, 0, -s * mean.x(), 0, s, -s * mean.y(), 0, 0, 1;
  return t;
}

// Least-squares map from lattice cells to image positions: affine while there are few cells (a
// small patch says little about perspective, and noise would invent some), then a normalised DLT
// homography.
Eigen::Matrix3d fit_map(const std::vector<Vec2>& from, const std::vector<Vec2>& to) {
  const Eigen::Matrix3d tf = normaliser(from);
  const Eigen::Matrix3d tt = normaliser(to);
  const auto n = static_cast<Eigen::Index>(from.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
  if (n < kHomographyCells) {
    Eigen::MatrixXd a(n, 3);
    Eigen::MatrixXd b(n, 2);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Vec2 f = apply(tf, from[static_cast<std::size_t>(k)]);
      const Vec2 t = apply(tt, to[static_cast<std::size_t>(k)]);
      a.row(k) << f.x(), f.y(), 1;
      b.row(k) << t.x(), t.y();
    }
    const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(b);  // 3 x 2
    h.topRows<2>() = x.transpose();
  } else {
    // The DLT's least singular vector, as the least eigenvector of A^T A: 9 x 9 whatever the
    // number of cells, and well enough conditioned once both point sets are normalised.
    using Row = Eigen::Matrix<double, 9, 1>;
    Eigen::Matrix<double, 9, 9> ata = Eigen::Matrix<double, 9, 9>::Zero();
    for (Eigen::Index k = 0; k < n; ++k) {
      const Vec2 f = apply(tf, from[static_cast<std::size_t>(k)]);
      const Vec2 t = apply(tt, to[static_cast<std::size_t>(k)]);
      Row r1;
      Row r2;
      r1 << f.x(), f.y(), 1, 0, 0, 0, -t.x() * f.x(), -t.x() * f.y(), -t.x();
      r2 << 0, 0, 0, f.x(), f.y(), 1, -t.y() * f.x(), -t.y() * f.y(), -t.y();
      ata.selfadjointView<Eigen::Lower>().rankUpdate(r1);
      ata.selfadjointView<Eigen::Lower>().rankUpdate(r2);
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(ata.selfadjointView<Eigen::Lower>());
    const Row v = eig.eigenvectors().col(0);  // eigenvalues ascend
    h << v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7), v(8);
  }
  return tt.inverse() * h * tf;
}

// Nearest-point queries over dots sorted by u: a query scans the strip |u - q.u| <= r, which for a
// grid holds about one column of dots.
class StripIndex {
 public:
  explicit StripIndex(const std::vector<Vec2>& points) : points_(points), order_(points.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), [&](int a, int b) { return at(a).x() < at(b).x(); });
    for (const int i : order_) xs_.push_back(at(i).x());
  }

  // The nearest point within r of q that is not taken, or -1.
  int nearest_free(const Vec2& q, double r, const std::vector<char>& taken) const {
    int best = -1;
    double best_d2 = r * r;
    for (auto k = static_cast<std::size_t>(std::lower_bound(xs_.begin(), xs_.end(), q.x() - r) - xs_.begin());
         k < xs_.size() && xs_[k] <= q.x() + r; ++k) {
      const int i = order_[k];
      const double d2 = (at(i) - q).squaredNorm();
      if (d2 <= best_d2 && !taken[static_cast<std::size_t>(i)]) {
        best = i;
        best_d2 = d2;
      }
    }
    return best;
  }

 private:
  const Vec2& at(int i) const { return points_[static_cast<std::size_t>(i)]; }
  const std::vector<Vec2>& points_;
  std::vector<int> order_;
  std::vector<double> xs_;
};

Eigen::Matrix3d fit_cells(const std::map<Cell, int>& cells, const std::vector<Vec2>& pts) {
  std::vector<Vec2> from;
  std::vector<Vec2> to;
  for (const auto& [cell, dot] : cells) {
    from.push_back(as_vec(cell));
    to.push_back(pts[static_cast<std::size_t>(dot)]);
  }
  return fit_map(from, to);
}

struct Prediction {
  Vec2 at;           // where cell c's dot should be
  double tolerance;  // how far from there it may be
};

// Cell c's dot as the map h and the cell's assigned neighbours (not c itself) predict it: h's
// position corrected by the neighbours' mean residual, so that what h cannot follow (lens
// distortion, an early affine map under perspective) is taken from close by. Nothing without an
// assigned neighbour or where h is degenerate.
std::optional<Prediction> predict(const Eigen::Matrix3d& h, const std::map<Cell, int>& cells,
                                  const std::vector<Vec2>& pts, const Cell& c) {
  const Vec2 at = as_vec(c);
  Vec2 residual = Vec2::Zero();
  int known = 0;
  for (const auto& [di, dj] : kNeighbours) {
    const auto it = cells.find({c.first + di, c.second + dj});
    if (it == cells.end()) continue;
    residual += pts[static_cast<std::size_t>(it->second)] - apply(h, as_vec(it->first));
    ++known;
  }
  // The spacing to the nearest lattice neighbour here, whichever direction that is.
  double spacing = INFINITY;
  for (const Vec2& d : {Vec2(1, 0), Vec2(0, 1), Vec2(1, 1), Vec2(1, -1)}) {
    spacing = std::min(spacing, (apply(h, at + d) - apply(h, at - d)).norm() / 2);
  }
  const Vec2 model = apply(h, at);
  if (known == 0 || !model.allFinite() || !std::isfinite(residual.x() + residual.y()) || !std::isfinite(spacing)) {
    return std::nullopt;
  }
  return Prediction{model + residual / known, kSnap * spacing};
}

// Cells of the lattice grown from one seed, each holding the index of its dot.
std::map<Cell, int> grow_lattice(const std::vector<Vec2>& pts, const StripIndex& index, int seed) {
  const Vec2& p = pts[static_cast<std::size_t>(seed)];
  std::vector<std::pair<double, int>> near;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d2 = (pts[i] - p).squaredNorm();
    if (d2 > 0) near.emplace_back(d2, static_cast<int>(i));
  }
  const auto k = std::min<std::size_t>(kSeedNeighbours, near.size());
  std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
  if (k < 2) return {};
  const int first = near[0].second;
  const Vec2 b1 = pts[static_cast<std::size_t>(first)] - p;
  int second = -1;
  for (std::size_t n = 1; n < k && second < 0; ++n) {
    const Vec2 b2 = pts[static_cast<std::size_t>(near[n].second)] - p;
    if (std::abs(cross(b1, b2)) > kMinSinBasis * b1.norm() * b2.norm()) second = near[n].second;
  }
  if (second < 0) return {};

  std::map<Cell, int> cells{{{0, 0}, seed}, {{1, 0}, first}, {{0, 1}, second}};
  std::vector<char> taken(pts.size(), 0);
  for (const auto& [cell, dot] : cells) taken[static_cast<std::size_t>(dot)] = 1;
  // Unassigned cells next to assigned ones. A cell that finds no dot stays, for a later, better map.
  std::set<Cell> frontier;
  const auto add_neighbours = [&](const Cell& cell) {
    for (const auto& [di, dj] : kNeighbours) {
      const Cell c{cell.first + di, cell.second + dj};
      if (!cells.contains(c)) frontier.insert(c);
    }
  };
  for (const auto& [cell, dot] : cells) add_neighbours(cell);
  for (bool grew = true; grew;) {
    grew = false;
    const Eigen::Matrix3d h = fit_cells(cells, pts);
    std::vector<Cell> added;
    for (const Cell& c : frontier) {
      const auto guess = predict(h, cells, pts, c);
      const int dot = guess ? index.nearest_free(guess->at, guess->tolerance, taken) : -1;
      if (dot < 0) continue;
      cells.emplace(c, dot);
      taken[static_cast<std::size_t>(dot)] = 1;
      added.push_back(c);
      grew = true;
    }
    for (const Cell& c : added) frontier.erase(c);
    for (const Cell& c : added) add_neighbours(c);
  }

  // Re-snap: a cell taken early, from a map fitted to a small patch and extrapolated, may hold a
  // stray that lay nearer that rough prediction than its dot did. Now that the map is fitted to
  // every cell, each cell takes the free dot nearest its neighbours' prediction, until none changes.
  for (int pass = 0; pass < kResnapPasses; ++pass) {
    const Eigen::Matrix3d h = fit_cells(cells, pts);
    bool changed = false;
    for (auto& [c, dot] : cells) {
      const auto guess = predict(h, cells, pts, c);
      if (!guess) continue;
      taken[static_cast<std::size_t>(dot)] = 0;
      const int best = index.nearest_free(guess->at, guess->tolerance, taken);
      if (best >= 0 && best != dot) {
        dot = best;
        changed = true;
      }
      taken[static_cast<std::size_t>(dot)] = 1;
    }
    if (!changed) break;
  }
  return cells;
}

struct Window {
  std::vector<int> dots;  // the window's dots, row by row: index b * width + a
  int width = 0;
  int height = 0;
};

// The cols x rows (or rows x cols) windows, in every lattice basis with small coefficients, whose
// every cell holds a dot; the same set of dots found in two bases counts once.
std::vector<Window> full_windows(const std::map<Cell, int>& cells, int cols, int rows) {
  std::vector<Cell> directions;  // primitive, one of each +-pair
  for (int x = 0; x <= kMaxBasisCoefficient; ++x) {
    for (int y = -kMaxBasisCoefficient; y <= kMaxBasisCoefficient; ++y) {
      if ((x == 0 && y <= 0) || std::gcd(x, y) != 1) continue;
      directions.emplace_back(x, y);
    }
  }
  std::vector<Window> found;
  std::set<std::vector<int>> seen;
  for (std::size_t ku = 0; ku < directions.size(); ++ku) {
    for (std::size_t kw = ku + 1; kw < directions.size(); ++kw) {
      const auto [ux, uy] = directions[ku];
      const auto [wx, wy] = directions[kw];
      const int det = ux * wy - uy * wx;
      if (det != 1 && det != -1) continue;
      // Coordinates in the basis (u, w): the inverse of an integer matrix of determinant +-1.
      std::vector<std::pair<Cell, int>> local;
      int a0 = std::numeric_limits<int>::max(), b0 = a0, a1 = std::numeric_limits<int>::min(), b1 = a1;
      for (const auto& [c, dot] : cells) {
        const int a = det * (wy * c.first - wx * c.second);
        const int b = det * (-uy * c.first + ux * c.second);
        local.push_back({{a, b}, dot});
        a0 = std::min(a0, a), a1 = std::max(a1, a), b0 = std::min(b0, b), b1 = std::max(b1, b);
      }
      const int w = a1 - a0 + 1;
      const int h = b1 - b0 + 1;
      std::vector<int> occupant(static_cast<std::size_t>(w) * h, -1);
      for (const auto& [c, dot] : local) occupant[static_cast<std::size_t>(c.second - b0) * w + (c.first - a0)] = dot;
      // Summed-area table of occupancy: a window is full when its sum is its size.
      std::vector<int> sat(static_cast<std::size_t>(w + 1) * (h + 1), 0);
      const auto i = [w](int x, int y) { return static_cast<std::size_t>(y) * (w + 1) + x; };
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          sat[i(x + 1, y + 1)] = sat[i(x, y + 1)] + sat[i(x + 1, y)] - sat[i(x, y)] +
                                 (occupant[static_cast<std::size_t>(y) * w + x] >= 0 ? 1 : 0);
        }
      }
      for (const auto& [ww, wh] : {std::pair{cols, rows}, std::pair{rows, cols}}) {
        for (int y = 0; y + wh <= h; ++y) {
          for (int x = 0; x + ww <= w; ++x) {
            if (sat[i(x + ww, y + wh)] - sat[i(x, y + wh)] - sat[i(x + ww, y)] + sat[i(x, y)] != ww * wh) continue;
            Window win{{}, ww, wh};
            for (int yy = y; yy < y + wh; ++yy) {
              for (int xx = x; xx < x + ww; ++xx) win.dots.push_back(occupant[static_cast<std::size_t>(yy) * w + xx]);
            }
            std::vector<int> key = win.dots;
            std::sort(key.begin(), key.end());
            if (seen.insert(std::move(key)).second) found.push_back(std::move(win));
          }
        }
      }
    }
  }
  return found;
}

// The labelling the header documents, from a window's (a, b) cells.
std::optional<std::vector<Vec2>> label(const Window& win, const std::vector<Vec2>& pts, int cols, int rows) {
  std::optional<std::vector<Vec2>> best;
  double best_score = -INFINITY;
  for (const bool transpose : {false, true}) {
    const int p_size = transpose ? win.height : win.width;
    const int q_size = transpose ? win.width : win.height;
    if (p_size != cols || q_size != rows) continue;
    for (const bool flip_i : {false, true}) {
      for (const bool flip_j : {false, true}) {
        std::vector<Vec2> out(static_cast<std::size_t>(cols) * rows);
        for (int b = 0; b < win.height; ++b) {
          for (int a = 0; a < win.width; ++a) {
            const int p = transpose ? b : a;
            const int q = transpose ? a : b;
            const int i = flip_i ? cols - 1 - p : p;
            const int j = flip_j ? rows - 1 - q : q;
            out[static_cast<std::size_t>(j) * cols + i] =
                pts[static_cast<std::size_t>(win.dots[static_cast<std::size_t>(b) * win.width + a])];
          }
        }
        // The axes as the mean of the grid's first-to-last spans: well defined under perspective,
        // where the steps shrink across the grid but keep their sense.
        Vec2 col_dir = Vec2::Zero();
        Vec2 row_dir = Vec2::Zero();
        for (int j = 0; j < rows; ++j) {
          col_dir += out[static_cast<std::size_t>(j) * cols + cols - 1] - out[static_cast<std::size_t>(j) * cols];
        }
        for (int i = 0; i < cols; ++i) {
          row_dir += out[static_cast<std::size_t>(rows - 1) * cols + i] - out[static_cast<std::size_t>(i)];
        }
        if (!(cross(col_dir, row_dir) < 0)) continue;
        const double score = col_dir.x() / col_dir.norm();
        if (score > best_score) {
          best_score = score;
          best = std::move(out);
        }
      }
    }
  }
  return best;
}

}  // namespace

std::optional<std::vector<Eigen::Vector2d>> order_dot_grid(const std::vector<Dot>& dots, int cols, int rows) {
  if (cols < 2 || rows < 2) return std::nullopt;  // a single row or column has no handedness
  const auto wanted = static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);

  std::vector<double> areas;
  for (const auto& d : dots) {
    if (d.centre.allFinite()) areas.push_back(d.area);
  }
  if (areas.size() < wanted) return std::nullopt;
  const auto mid = areas.begin() + static_cast<std::ptrdiff_t>(areas.size() / 2);
  std::nth_element(areas.begin(), mid, areas.end());
  const double median = *mid;
  std::vector<Vec2> pts;
  for (const auto& d : dots) {
    const bool area_ok = median <= 0 || (d.area >= median / kAreaRatio && d.area <= median * kAreaRatio);
    if (d.centre.allFinite() && area_ok) pts.push_back(d.centre);
  }
  if (pts.size() < wanted) return std::nullopt;

  // Seeds nearest the middle of the dots first: with few strays the first seed is almost always a
  // dot well inside the grid.
  std::vector<double> us;
  std::vector<double> vs;
  for (const auto& p : pts) us.push_back(p.x()), vs.push_back(p.y());
  std::nth_element(us.begin(), us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2), us.end());
  std::nth_element(vs.begin(), vs.begin() + static_cast<std::ptrdiff_t>(vs.size() / 2), vs.end());
  const Vec2 middle(us[us.size() / 2], vs[vs.size() / 2]);
  std::vector<int> seeds(pts.size());
  std::iota(seeds.begin(), seeds.end(), 0);
  std::sort(seeds.begin(), seeds.end(), [&](int a, int b) {
    return (pts[static_cast<std::size_t>(a)] - middle).squaredNorm() <
           (pts[static_cast<std::size_t>(b)] - middle).squaredNorm();
  });

  // A lattice grown from a stray can still hold every dot: a stray halfway between two dots seeds a
  // lattice twice as fine, with the dots on every other cell. So a lattice without a full window
  // says nothing about the next seed's, and every seed (up to kMaxSeeds) gets its own growth.
  const StripIndex index(pts);
  const auto seeds_to_try = std::min<std::size_t>(seeds.size(), kMaxSeeds);
  for (std::size_t k = 0; k < seeds_to_try; ++k) {
    const auto cells = grow_lattice(pts, index, seeds[k]);
    if (cells.size() < wanted) continue;  // a stray seed, or a wrong basis: try another
    const auto windows = full_windows(cells, cols, rows);
    if (windows.size() > 1) return std::nullopt;  // strays that cannot be told from dots
    if (windows.size() == 1) return label(windows.front(), pts, cols, rows);
  }
  return std::nullopt;
}

}  // namespace neopipe::calib
