#include "nav/mapmaker/reliability_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "nav/common/landmarks.hpp"

namespace neopipe::nav::mapmaker {
namespace {

std::vector<Eigen::Vector2d> random_view(int visible, std::mt19937_64& rng) {
  constexpr double kMargin = 0.05, kSeparation = 0.04;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> points{{kMargin, kMargin}};
  while (static_cast<int>(points.size()) < visible) {
    const Eigen::Vector2d p(unit(rng), unit(rng));
    const bool clear = std::all_of(points.begin(), points.end(),
                                   [&](const Eigen::Vector2d& q) { return (p - q).norm() >= kSeparation; });
    if (clear) points.push_back(p);
  }
  return points;
}

}  // namespace

SelectionSample simulate_selection(int visible, double relative_sigma, int trials, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, relative_sigma);
  SelectionSample sample{visible, relative_sigma, trials, 0};
  std::vector<Eigen::Vector2d> measured;
  for (int i = 0; i < trials; ++i) {
    const std::vector<Eigen::Vector2d> truth = random_view(visible, rng);
    measured = truth;
    for (Eigen::Vector2d& p : measured) p += Eigen::Vector2d(noise(rng), noise(rng));
    if (isolated_landmark({truth, 0}) == isolated_landmark({measured, 0})) ++sample.agreed;
  }
  return sample;
}

SelectionFit fit_selection(std::span<const SelectionSample> samples) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int used = 0;
  for (const SelectionSample& s : samples) {
    const double r = s.reliability();
    if (s.visible <= 2 || !(s.relative_sigma > 0) || s.agreed == 0 || s.agreed == s.trials) continue;
    const Eigen::Vector3d x(1.0, std::log(s.visible - 2.0), std::log(s.relative_sigma));
    const double y = std::log(1.0 / r - 1.0);
    const double w = s.trials * r * (1 - r);
    normal += w * x * x.transpose();
    rhs += w * y * x;
    ++used;
  }
  if (used < 3) throw std::invalid_argument("fit_selection: fewer than 3 samples with 0 < R < 1");
  const Eigen::Vector3d c = normal.ldlt().solve(rhs);
  SelectionFit fit{{c[0], c[1], c[2]}, 0, 0};
  double sum = 0;
  for (const SelectionSample& s : samples) {
    const double e = std::abs(fit.model(s.visible, s.relative_sigma) - s.reliability());
    sum += e * e;
    fit.max_error = std::max(fit.max_error, e);
  }
  fit.rms_error = samples.empty() ? 0 : std::sqrt(sum / static_cast<double>(samples.size()));
  return fit;
}

double simulate_trajectory(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors,
                           int trials, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> position(0.0, errors.sigma);
  const double turn_sd = std::hypot(errors.translation_per_mm, errors.rotation_per_mm * trajectory.slide / 2);
  std::normal_distribution<double> turn(0.0, turn_sd);
  const Eigen::Vector2d reference = views.position(trajectory.from.object);
  const Eigen::Vector2d landmark = views.position(trajectory.via);
  const double towards = trajectory.direction == Direction::positive ? 1.0 : -1.0;
  const std::uint32_t known[] = {std::min(trajectory.from.object, trajectory.via),
                                 std::max(trajectory.from.object, trajectory.via)};
  int agreed = 0;
  const std::span<const Eigen::Vector2d> surveyed = views.grid().objects();
  std::vector<Eigen::Vector2d> truth(surveyed.begin(), surveyed.end());
  for (int i = 0; i < trials; ++i) {
    const Eigen::Vector2d e1(position(rng), position(rng));
    const Eigen::Vector2d e2(position(rng), position(rng));
    // Every other object is where the survey put it only to within its own error.
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const bool known_object = k == trajectory.from.object || k == trajectory.via;
      truth[k] =
          known_object ? surveyed[k] : Eigen::Vector2d(surveyed[k] + Eigen::Vector2d(position(rng), position(rng)));
    }
    const ObjectGrid grid(truth, views.grid().cell());
    const Eigen::Vector2d seen = towards * ((landmark + e2) - (reference + e1));
    const double angle = std::atan2(seen.y(), seen.x()) + turn(rng);
    // The navigator holds the reference where it really is (surveyed + e1): the window moves with it.
    const auto hit = first_entering(grid, views.window(), views.origin(trajectory.from) + e1,
                                    Eigen::Vector2d(std::cos(angle), std::sin(angle)), reference, known);
    if (hit && hit->object == trajectory.to) ++agreed;
  }
  return trials > 0 ? static_cast<double>(agreed) / trials : 0.0;
}

}  // namespace neopipe::nav::mapmaker
