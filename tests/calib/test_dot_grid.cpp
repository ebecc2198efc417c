// Dot-grid targets: order_dot_grid on synthetic centroid sets (random rotations and strong
// perspective, noise, shuffled, strays, a missing dot, a mirror image) against the labels they were
// generated with and the rotation rule of calib/dot_grid.hpp; find_dot_grid on targets rendered by
// the simulator against their projected dot centres, and against cv::findCirclesGrid.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <vector>

#include "calib/dot_grid.hpp"
#include "calib/dot_grid_detector.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/target_renderer.hpp"

namespace calib = neopipe::calib;
namespace sim = neopipe::sim;
using Vec2 = Eigen::Vector2d;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Where the grid's point (i, j) (fractional allowed) appears in the image.
using GridView = std::function<Vec2(double i, double j)>;

// What the header's rule says, computed from the noise-free view rather than the dots given: for
// every symmetry of the cols x rows grid that keeps its shape, the output label (i, j) comes from
// generating label g(i, j); keep those whose axes satisfy cross(col_dir, row_dir) < 0 and take the
// column axis most nearly along +u. Under perspective an axis's direction changes across the grid;
// as in calib/dot_grid.cpp it is taken as the mean first-to-last span of the rows (columns). Returns
// every labelling within `tie` of the best cosine (more than one only near a tie, where the dots'
// noise may decide), as maps from output index to generating index.
std::vector<std::vector<int>> expected_labellings(const GridView& view, int cols, int rows, double tie = 0.01) {
  Vec2 di = Vec2::Zero();
  Vec2 dj = Vec2::Zero();
  for (int j = 0; j < rows; ++j) di += view(cols - 1, j) - view(0, j);
  for (int i = 0; i < cols; ++i) dj += view(i, rows - 1) - view(i, 0);
  struct Candidate {
    double score;
    std::vector<int> map;
  };
  std::vector<Candidate> ok;
  for (const bool transpose : {false, true}) {
    if (transpose && cols != rows) continue;
    for (const bool fi : {false, true}) {
      for (const bool fj : {false, true}) {
        // Output (i, j) -> p = fi ? cols-1-i : i, q = fj ? rows-1-j : j; source (p, q) or (q, p).
        const double si = fi ? -1 : 1;
        const double sj = fj ? -1 : 1;
        const Vec2 col_dir = transpose ? Vec2(si * dj) : Vec2(si * di);
        const Vec2 row_dir = transpose ? Vec2(sj * di) : Vec2(sj * dj);
        if (!(cross(col_dir, row_dir) < 0)) continue;
        std::vector<int> map(static_cast<size_t>(cols * rows));
        for (int j = 0; j < rows; ++j) {
          for (int i = 0; i < cols; ++i) {
            const int p = fi ? cols - 1 - i : i;
            const int q = fj ? rows - 1 - j : j;
            map[static_cast<size_t>(j * cols + i)] = transpose ? p * cols + q : q * cols + p;
          }
        }
        ok.push_back({col_dir.x() / col_dir.norm(), std::move(map)});
      }
    }
  }
  double best = -2;
  for (const auto& c : ok) best = std::max(best, c.score);
  std::vector<std::vector<int>> out;
  for (auto& c : ok) {
    if (c.score >= best - tie) out.push_back(std::move(c.map));
  }
  return out;
}

bool handedness_holds(const std::vector<Vec2>& grid, int cols, int rows) {
  Vec2 col_dir = Vec2::Zero();
  Vec2 row_dir = Vec2::Zero();
  for (int j = 0; j < rows; ++j)
    col_dir += grid[static_cast<size_t>(j * cols + cols - 1)] - grid[static_cast<size_t>(j * cols)];
  for (int i = 0; i < cols; ++i)
    row_dir += grid[static_cast<size_t>((rows - 1) * cols + i)] - grid[static_cast<size_t>(i)];
  return cross(col_dir, row_dir) < 0;
}

// --- Synthetic centroid sets ------------------------------------------------------------------

// A cols x rows grid of pitch 25 mm seen by a pinhole camera (f = 1000 px) at `distance` mm: turned
// theta about the optical axis, tilted `tilt` about an in-plane axis at `axis` (degrees). Label
// (i, j) is at target point ((i - ci) pitch, (j - cj) pitch) with j North, so seen from the front
// the labels have the header's handedness; `mirrored` shows the target from behind.
struct SyntheticView {
  int cols = 0;
  int rows = 0;
  double theta = 0;
  double tilt = 0;
  double axis = 0;
  double distance = 900;
  bool mirrored = false;

  Eigen::Vector3d point(double i, double j) const {
    constexpr double pitch = 25;
    const Eigen::Matrix3d r =
        (Eigen::AngleAxisd(theta * kDeg, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(tilt * kDeg, Eigen::Vector3d(std::cos(axis * kDeg), std::sin(axis * kDeg), 0)))
            .toRotationMatrix();
    return r * Eigen::Vector3d((i - (cols - 1) / 2.0) * pitch, (j - (rows - 1) / 2.0) * pitch, 0) +
           Eigen::Vector3d(0, 0, distance);
  }
  Vec2 pixel(double i, double j) const {
    const Eigen::Vector3d p = point(i, j);
    const double v = 1000 * p.y() / p.z();
    return {640 + 1000 * p.x() / p.z(), mirrored ? 480 + v : 480 - v};  // image v grows downwards
  }
  // A dot's area: 60 px^2 at 900 mm face on, smaller when tilted or far.
  double area(double i, double j) const { return 60 * std::cos(tilt * kDeg) * std::pow(900 / point(i, j).z(), 2); }
};

struct Synthetic {
  std::vector<Vec2> truth;       // noisy centres in generating order (index j * cols + i)
  std::vector<calib::Dot> dots;  // what order_dot_grid is given: shuffled, with strays
};

Synthetic make_dots(const SyntheticView& view, std::mt19937& rng, double noise = 0.2) {
  std::normal_distribution<double> n(0, noise);
  Synthetic s;
  for (int j = 0; j < view.rows; ++j) {
    for (int i = 0; i < view.cols; ++i) {
      const Vec2 c = view.pixel(i, j) + Vec2(n(rng), n(rng));
      s.truth.push_back(c);
      s.dots.push_back({c, view.area(i, j) * std::exp(n(rng) / 4)});
    }
  }
  return s;
}

double min_spacing(const std::vector<Vec2>& pts) {
  double best = INFINITY;
  for (size_t a = 0; a < pts.size(); ++a) {
    for (size_t b = a + 1; b < pts.size(); ++b) best = std::min(best, (pts[a] - pts[b]).norm());
  }
  return best;
}

// About 10% extra blobs: half of a very different area anywhere (also on top of dots), half of a
// dot's area anywhere around and inside the grid except within 0.45 of the smallest dot spacing of
// a dot, where a blob of a dot's size cannot be told from that dot.
void add_strays(Synthetic& s, std::mt19937& rng) {
  Eigen::AlignedBox2d box;
  for (const auto& p : s.truth) box.extend(p);
  const double margin = 2 * min_spacing(s.truth);
  std::uniform_real_distribution<double> u(box.min().x() - margin, box.max().x() + margin);
  std::uniform_real_distribution<double> v(box.min().y() - margin, box.max().y() + margin);
  std::vector<double> areas;
  for (const auto& d : s.dots) areas.push_back(d.area);
  std::sort(areas.begin(), areas.end());
  const double dot_area = areas[areas.size() / 2];
  const double keep_off = 0.45 * min_spacing(s.truth);
  const int strays = std::max(2, static_cast<int>(s.truth.size()) / 10);
  for (int k = 0; k < strays; ++k) {
    if (k % 2 == 0) {
      s.dots.push_back({Vec2(u(rng), v(rng)), dot_area * (k % 4 == 0 ? 0.08 : 8.0)});
      continue;
    }
    for (;;) {
      const Vec2 p(u(rng), v(rng));
      const bool clear =
          std::all_of(s.truth.begin(), s.truth.end(), [&](const Vec2& t) { return (t - p).norm() > keep_off; });
      if (clear) {
        s.dots.push_back({p, dot_area});
        break;
      }
    }
  }
}

// The result is one of the rule's labellings of the generating labels, index by index.
::testing::AssertionResult labelled_as_the_rule_says(const std::optional<std::vector<Vec2>>& found,
                                                     const std::vector<Vec2>& truth, const GridView& view, int cols,
                                                     int rows) {
  if (!found) return ::testing::AssertionFailure() << "no grid found";
  if (found->size() != truth.size()) return ::testing::AssertionFailure() << found->size() << " points";
  if (!handedness_holds(*found, cols, rows)) return ::testing::AssertionFailure() << "handedness does not hold";
  for (const auto& map : expected_labellings(view, cols, rows)) {
    bool same = true;
    for (size_t k = 0; k < map.size() && same; ++k) same = (*found)[k] == truth[static_cast<size_t>(map[k])];
    if (same) return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "labelling differs from the rule's";
}

struct GridSize {
  int cols;
  int rows;
};
constexpr GridSize kSizes[] = {{4, 3}, {7, 7}, {11, 8}};

SyntheticView random_view(GridSize g, std::mt19937& rng, double max_tilt) {
  std::uniform_real_distribution<double> angle(0, 360);
  std::uniform_real_distribution<double> tilt(0, max_tilt);
  std::uniform_real_distribution<double> distance(450, 1100);  // near: strong convergence
  return {g.cols, g.rows, angle(rng), tilt(rng), angle(rng), distance(rng), false};
}

TEST(OrderDotGrid, RandomRotationsAndPerspectiveShuffled) {
  std::mt19937 rng(5);
  for (const auto g : kSizes) {
    for (int trial = 0; trial < 60; ++trial) {
      // A third face on, the rest tilted up to 60 degrees: strong perspective.
      const SyntheticView view = random_view(g, rng, trial < 20 ? 0 : 60);
      Synthetic s = make_dots(view, rng);
      std::shuffle(s.dots.begin(), s.dots.end(), rng);
      const auto found = calib::order_dot_grid(s.dots, g.cols, g.rows);
      const GridView gv = [&](double i, double j) { return view.pixel(i, j); };
      EXPECT_TRUE(labelled_as_the_rule_says(found, s.truth, gv, g.cols, g.rows))
          << g.cols << "x" << g.rows << " theta " << view.theta << " tilt " << view.tilt << " about " << view.axis;
    }
  }
}

TEST(OrderDotGrid, UprightGridKeepsItsOwnLabels) {
  // Face up under a North-up camera, turned less than 45 degrees: i East, j North, as generated.
  std::mt19937 rng(6);
  for (const auto g : kSizes) {
    for (const double theta : {-40.0, -10.0, 0.0, 20.0, 44.0}) {
      const SyntheticView view{g.cols, g.rows, theta, 30, 70, 900, false};
      Synthetic s = make_dots(view, rng);
      std::shuffle(s.dots.begin(), s.dots.end(), rng);
      const auto found = calib::order_dot_grid(s.dots, g.cols, g.rows);
      ASSERT_TRUE(found) << g.cols << "x" << g.rows << " theta " << theta;
      EXPECT_EQ(*found, s.truth) << g.cols << "x" << g.rows << " theta " << theta;
    }
  }
}

TEST(OrderDotGrid, TurnedHalfWayRoundIsRelabelledByTheRotation) {
  // Turned 180 degrees the upright labels would put the column axis along -u: the rule picks the
  // 180-degree rotation of the labels instead; a square grid turned 90 degrees picks a quarter turn.
  std::mt19937 rng(7);
  const SyntheticView half{11, 8, 175, 20, 10, 900, false};
  const Synthetic s = make_dots(half, rng);
  const auto found = calib::order_dot_grid(s.dots, 11, 8);
  ASSERT_TRUE(found);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 11; ++i)
      EXPECT_EQ((*found)[static_cast<size_t>(j * 11 + i)], s.truth[static_cast<size_t>((7 - j) * 11 + 10 - i)]);
  }
  const SyntheticView quarter{7, 7, 95, 0, 0, 900, false};  // column axis (East) now points up the image
  const Synthetic q = make_dots(quarter, rng);
  const auto turned = calib::order_dot_grid(q.dots, 7, 7);
  ASSERT_TRUE(turned);
  // The output's column axis is the generating row axis reversed: (i, j) <- (j, 6 - i).
  for (int j = 0; j < 7; ++j) {
    for (int i = 0; i < 7; ++i)
      EXPECT_EQ((*turned)[static_cast<size_t>(j * 7 + i)], q.truth[static_cast<size_t>((6 - i) * 7 + j)]);
  }
}

TEST(OrderDotGrid, StrayBlobsAreRejected) {
  std::mt19937 rng(8);
  for (const auto g : kSizes) {
    for (int trial = 0; trial < 40; ++trial) {
      const SyntheticView view = random_view(g, rng, 60);
      Synthetic s = make_dots(view, rng);
      add_strays(s, rng);
      std::shuffle(s.dots.begin(), s.dots.end(), rng);
      const auto found = calib::order_dot_grid(s.dots, g.cols, g.rows);
      const GridView gv = [&](double i, double j) { return view.pixel(i, j); };
      EXPECT_TRUE(labelled_as_the_rule_says(found, s.truth, gv, g.cols, g.rows))
          << g.cols << "x" << g.rows << " theta " << view.theta << " tilt " << view.tilt << " with "
          << s.dots.size() - s.truth.size() << " strays";
    }
  }
}

TEST(OrderDotGrid, StraysOnTheLatticeBeyondTheGrid) {
  // Blobs of a dot's size exactly where the grid would continue: a partial extra row is told from
  // the grid (no full window contains it); a whole extra row makes two grids, which is refused.
  std::mt19937 rng(9);
  const SyntheticView view{7, 5, 12, 35, 40, 900, false};
  Synthetic s = make_dots(view, rng);
  const GridView gv = [&](double i, double j) { return view.pixel(i, j); };
  for (int i = 0; i < 6; ++i) s.dots.push_back({view.pixel(i, 5), s.dots.front().area});
  s.dots.push_back({view.pixel(-1, 2), s.dots.front().area});
  EXPECT_TRUE(labelled_as_the_rule_says(calib::order_dot_grid(s.dots, 7, 5), s.truth, gv, 7, 5));
  s.dots.push_back({view.pixel(6, 5), s.dots.front().area});  // the extra row is now complete
  EXPECT_FALSE(calib::order_dot_grid(s.dots, 7, 5));
}

TEST(OrderDotGrid, MissingDotGivesNothing) {
  std::mt19937 rng(10);
  for (const auto g : kSizes) {
    for (int trial = 0; trial < 10; ++trial) {
      const SyntheticView view = random_view(g, rng, 50);
      Synthetic s = make_dots(view, rng);
      // A corner in the first trial (the hardest to notice), then anywhere. A stray of a dot's area
      // far off makes up the count, so the lattice is grown (from every seed) and found wanting.
      const auto gone = trial == 0 ? 0 : std::uniform_int_distribution<size_t>(0, s.dots.size() - 1)(rng);
      const double area = s.dots[gone].area;
      s.dots.erase(s.dots.begin() + static_cast<std::ptrdiff_t>(gone));
      s.dots.push_back({Vec2(1e4, 1e4), area});
      s.dots.push_back({Vec2(-1e4, 1e4), 1000});
      EXPECT_FALSE(calib::order_dot_grid(s.dots, g.cols, g.rows)) << g.cols << "x" << g.rows << " without dot " << gone;
    }
  }
  EXPECT_FALSE(calib::order_dot_grid({}, 4, 3));
  EXPECT_FALSE(calib::order_dot_grid({{Vec2(0, 0), 10}, {Vec2(10, 0), 10}}, 2, 1));
}

TEST(OrderDotGrid, ClutterWithoutAGridGivesNothingQuickly) {
  // Thousands of dot-sized blobs at random: no grid, and the search stays bounded.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0, 1280);
  std::uniform_real_distribution<double> v(0, 960);
  std::vector<calib::Dot> clutter;
  for (int k = 0; k < 5000; ++k) clutter.push_back({Vec2(u(rng), v(rng)), 50});
  EXPECT_FALSE(calib::order_dot_grid(clutter, 11, 8));
  EXPECT_FALSE(calib::order_dot_grid(clutter, 4, 3));
}

TEST(OrderDotGrid, MirroredSetIsLabelledByARotationNotTheMirror) {
  // Seen from behind the generating labels have the wrong handedness: the result is still a
  // rotation in the image (column axis along +u, row axis up), so relative to the target's own
  // labels it is mirrored: row j is the target's row rows - 1 - j.
  std::mt19937 rng(11);
  for (const auto g : kSizes) {
    const SyntheticView view{g.cols, g.rows, 8, 25, 100, 900, true};
    Synthetic s = make_dots(view, rng);
    std::shuffle(s.dots.begin(), s.dots.end(), rng);
    const auto found = calib::order_dot_grid(s.dots, g.cols, g.rows);
    ASSERT_TRUE(found);
    EXPECT_TRUE(handedness_holds(*found, g.cols, g.rows));
    for (int j = 0; j < g.rows; ++j) {
      for (int i = 0; i < g.cols; ++i) {
        EXPECT_EQ((*found)[static_cast<size_t>(j * g.cols + i)],
                  s.truth[static_cast<size_t>((g.rows - 1 - j) * g.cols + i)]);
      }
    }
    const GridView gv = [&](double i, double j) { return view.pixel(i, j); };
    EXPECT_TRUE(labelled_as_the_rule_says(found, s.truth, gv, g.cols, g.rows));
  }
}

// --- Targets rendered by the simulator ---------------------------------------------------------

const sim::CalibrationTarget kTarget{sim::TargetKind::dots, 11, 8, 25, 9};

// The target centred on the workspace's centre (z above it), turned and tilted.
sim::TargetPose centred_pose(double z, double theta, double tilt_x = 0, double tilt_y = 0) {
  sim::TargetPose pose = sim::target_pose(0, 0, z, theta, tilt_x, tilt_y);
  const Eigen::Vector3d half((kTarget.cols - 1) * kTarget.pitch / 2, (kTarget.rows - 1) * kTarget.pitch / 2, 0);
  pose.translation = Eigen::Vector3d(250, 250, z) - pose.rotation * half;
  return pose;
}

struct Scene {
  sim::PinholeCamera camera = sim::make_global_camera({500, 500});
  cv::Mat image;
  std::vector<Vec2> truth;  // projected dot centres, the target's own order
  GridView view;            // the target's point (i, j) in the image
};

Scene render(const sim::TargetPose& pose, double noise_sigma) {
  Scene s;
  sim::ImageModel model;
  model.noise_sigma = noise_sigma;
  const sim::MarbleRenderer renderer(model, s.camera.size());
  s.image = sim::render_target(kTarget, pose, s.camera, renderer);
  s.truth = sim::projected_target_points(kTarget, pose, s.camera);
  s.view = [camera = s.camera, pose](double i, double j) {
    return *camera.project(pose.rotation * Eigen::Vector3d(i * kTarget.pitch, j * kTarget.pitch, 0) + pose.translation);
  };
  return s;
}

// RMS and largest distance between found and truth in the rule's labelling; -1 if none fits.
struct Accuracy {
  double rms = -1;
  double max = -1;
};

Accuracy accuracy(const std::vector<Vec2>& found, const Scene& s) {
  Accuracy best;
  for (const auto& map : expected_labellings(s.view, kTarget.cols, kTarget.rows)) {
    double sum2 = 0;
    double worst = 0;
    for (size_t k = 0; k < map.size(); ++k) {
      const double e = (found[k] - s.truth[static_cast<size_t>(map[k])]).norm();
      sum2 += e * e;
      worst = std::max(worst, e);
    }
    const double rms = std::sqrt(sum2 / static_cast<double>(map.size()));
    if (best.rms < 0 || rms < best.rms) best = {rms, worst};
  }
  return best;
}

// RMS distance from each point to the nearest truth point (for OpenCV's own ordering).
double rms_to_nearest(const std::vector<Vec2>& pts, const std::vector<Vec2>& truth) {
  double sum2 = 0;
  for (const auto& p : pts) {
    double best = INFINITY;
    for (const auto& t : truth) best = std::min(best, (p - t).norm());
    sum2 += best * best;
  }
  return std::sqrt(sum2 / static_cast<double>(pts.size()));
}

std::optional<std::vector<Vec2>> opencv_circles_grid(const cv::Mat& image) {
  cv::SimpleBlobDetector::Params p;
  p.blobColor = 255;  // bright dots
  p.minArea = 20;
  p.maxArea = 5000;
  const auto detector = cv::SimpleBlobDetector::create(p);
  std::vector<cv::Point2f> centres;
  if (!cv::findCirclesGrid(image, cv::Size(kTarget.cols, kTarget.rows), centres, cv::CALIB_CB_SYMMETRIC_GRID,
                           detector)) {
    return std::nullopt;
  }
  std::vector<Vec2> out;
  for (const auto& c : centres) out.emplace_back(c.x, c.y);
  return out;
}

struct PoseCase {
  const char* name;
  sim::TargetPose pose;
  bool upright;  // turned within 45 degrees of North-up: the target's own labels
};

std::vector<PoseCase> pose_cases() {
  return {{"flat theta -30", centred_pose(0, -30), true},
          {"flat theta 0", centred_pose(0, 0), true},
          {"flat theta 45", centred_pose(0, 45), true},
          {"flat theta 170", centred_pose(0, 170), false},
          {"tilted x 30 y -20 z 50", centred_pose(50, 0, 30, -20), true},
          {"tilted x 30 y -20 z 50 theta 120", centred_pose(50, 120, 30, -20), false}};
}

TEST(FindDotGrid, RenderedTargetsToAFewHundredthsOfAPixel) {
  for (const double noise : {0.0, 2.0}) {
    for (const auto& c : pose_cases()) {
      const Scene s = render(c.pose, noise);
      const auto found = calib::find_dot_grid(s.image, kTarget.cols, kTarget.rows);
      ASSERT_TRUE(found) << c.name << ", noise " << noise;
      ASSERT_EQ(found->size(), s.truth.size());
      EXPECT_TRUE(handedness_holds(*found, kTarget.cols, kTarget.rows)) << c.name;
      const Accuracy a = accuracy(*found, s);
      std::printf("find_dot_grid %-34s noise %.0f: RMS %.4f px, max %.4f px\n", c.name, noise, a.rms, a.max);
      EXPECT_GE(a.rms, 0) << c.name;
      EXPECT_LT(a.max, 0.1) << c.name << ", noise " << noise;
      if (noise == 0) {
        EXPECT_LT(a.rms, 0.04) << c.name;  // ~0.02 px expected noiseless
      }
      if (c.upright) {
        // The target's own order, index by index.
        for (size_t k = 0; k < s.truth.size(); ++k)
          EXPECT_LT(((*found)[k] - s.truth[k]).norm(), 0.1) << c.name << " dot " << k;
      }
    }
  }
}

TEST(FindDotGrid, TurnedHalfWayRoundIsTheTargetRotated) {
  const Scene s = render(centred_pose(0, 170), 2.0);
  const auto found = calib::find_dot_grid(s.image, kTarget.cols, kTarget.rows);
  ASSERT_TRUE(found);
  const int cols = kTarget.cols;
  const int rows = kTarget.rows;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const Vec2 truth = s.truth[static_cast<size_t>((rows - 1 - j) * cols + cols - 1 - i)];
      EXPECT_LT(((*found)[static_cast<size_t>(j * cols + i)] - truth).norm(), 0.1);
    }
  }
}

TEST(FindDotGrid, AgreesWithFindCirclesGridAndIsMoreAccurate) {
  int compared = 0;
  for (const double noise : {0.0, 2.0}) {
    for (const auto& c : pose_cases()) {
      const Scene s = render(c.pose, noise);
      const auto ours = calib::find_dot_grid(s.image, kTarget.cols, kTarget.rows);
      ASSERT_TRUE(ours) << c.name;
      const auto theirs = opencv_circles_grid(s.image);
      if (!theirs) {
        std::printf("findCirclesGrid %-34s noise %.0f: not found\n", c.name, noise);
        continue;
      }
      ++compared;
      // The same point set: every OpenCV centre within 0.5 px of one of ours.
      for (const auto& p : *theirs) EXPECT_LT(rms_to_nearest({p}, *ours), 0.5) << c.name;
      const double rms_ours = accuracy(*ours, s).rms;
      const double rms_theirs = rms_to_nearest(*theirs, s.truth);
      std::printf("%-34s noise %.0f: find_dot_grid RMS %.4f px, findCirclesGrid RMS %.4f px\n", c.name, noise, rms_ours,
                  rms_theirs);
      // Tilted, both carry the ~0.02 px by which a tilted disk's image centroid misses its projected
      // centre (measured: find_dot_grid is 0.007 px from the true image centroid there).
      EXPECT_LT(rms_ours, rms_theirs) << c.name;
    }
  }
  EXPECT_GT(compared, 0) << "findCirclesGrid found none of the targets";
}

TEST(FindDotGrid, DarkDotsOnALightBoardAndBgrFrames) {
  const Scene s = render(centred_pose(50, 20, 30, -20), 2.0);
  const auto gray = calib::find_dot_grid(s.image, kTarget.cols, kTarget.rows);
  ASSERT_TRUE(gray);
  cv::Mat bgr;
  cv::cvtColor(s.image, bgr, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(calib::find_dot_grid(bgr, kTarget.cols, kTarget.rows), gray);  // the engine's gray is cv::cvtColor's
  const cv::Mat inverted = 255 - s.image;
  const auto dark = calib::find_dot_grid(inverted, kTarget.cols, kTarget.rows);
  ASSERT_TRUE(dark);
  const Accuracy a = accuracy(*dark, s);
  std::printf("dark dots on a light board: RMS %.4f px, max %.4f px\n", a.rms, a.max);
  EXPECT_LT(a.max, 0.1);
}

TEST(FindDotGrid, NoTargetOrCutOffTargetGivesNothing) {
  const auto camera = sim::make_global_camera({500, 500});
  const sim::MarbleRenderer renderer(sim::ImageModel{}, camera.size());
  const cv::Mat empty = renderer.render({}, 10, camera, 0);
  EXPECT_FALSE(calib::find_dot_grid(empty, kTarget.cols, kTarget.rows));
  EXPECT_FALSE(calib::find_dot_grid(cv::Mat::zeros(480, 640, CV_8UC1), kTarget.cols, kTarget.rows));
  cv::Mat noise(480, 640, CV_8UC1);
  cv::randu(noise, 0, 256);
  EXPECT_FALSE(calib::find_dot_grid(noise, kTarget.cols, kTarget.rows));
  EXPECT_FALSE(calib::find_dot_grid(cv::Mat(), kTarget.cols, kTarget.rows));
  EXPECT_THROW(calib::find_dot_grid(cv::Mat::zeros(10, 10, CV_32F), kTarget.cols, kTarget.rows), std::invalid_argument);

  // Part of the target beyond the image's left edge (several columns), or its bottom edge (a row).
  sim::TargetPose left = centred_pose(0, 10);
  left.translation.x() -= 330;
  EXPECT_FALSE(calib::find_dot_grid(render(left, 2.0).image, kTarget.cols, kTarget.rows));
  sim::TargetPose bottom = centred_pose(0, 0);
  bottom.translation.y() -= 190;
  EXPECT_FALSE(calib::find_dot_grid(render(bottom, 2.0).image, kTarget.cols, kTarget.rows));
}

}  // namespace
