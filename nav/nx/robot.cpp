#include "nav/nx/robot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace neopipe::nav::nx {
namespace {

constexpr double kNxDegree = std::numbers::pi / 180;

// The value a range has at a probe: its own sector's when it stays within `tolerance`, else the
// nearest value of a neighbouring sector; 0 when none fits.
double follow_range(const Scan& probe, int sector, double value, double tolerance) {
  const double own = probe[static_cast<std::size_t>(sector)];
  if (own > 0 && std::abs(own - value) <= tolerance) return own;
  double best = 0;
  for (const int k : {sector - 1, sector + 1}) {
    const double v = probe[static_cast<std::size_t>((k + kSectors) % kSectors)];
    if (v > 0 && std::abs(v - value) <= tolerance && (best == 0 || std::abs(v - value) < std::abs(best - value))) {
      best = v;
    }
  }
  return best;
}

}  // namespace

double wrap180(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w <= -180) w += 360;
  if (w > 180) w -= 360;
  return w;
}

Robot::Robot(pipeline::io::FrameSource& ring, nav::Compass& compass, nav::Arm& arm, const NxConfig& config)
    : ring_(ring), compass_(compass), arm_(arm), config_(config) {
  read_heading();
}

Scan Robot::look(int reads) {
  const int n = reads > 0 ? reads : std::max(1, config_.reads);
  Scan sum{};
  std::array<int, kSectors> seen{};
  for (int i = 0; i < n; ++i) {
    const auto frame = ring_.next();
    if (!frame) throw std::runtime_error("the range ring stopped delivering frames");
    const cv::Mat& m = frame->image;
    if (m.rows != 1 || m.cols != kSectors || m.type() != CV_32FC1) {
      throw std::runtime_error("the range ring's frame is not 1 x 16 CV_32FC1");
    }
    ++frames_;
    for (int k = 0; k < kSectors; ++k) {
      const auto v = static_cast<double>(m.at<float>(0, k));
      if (v > 0) {
        sum[static_cast<std::size_t>(k)] += v;
        ++seen[static_cast<std::size_t>(k)];
      }
    }
  }
  // A sector counts when most reads saw something there: a marble at the edge of the range may
  // flicker in and out.
  Scan out{};
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (2 * seen[k] > n) out[k] = sum[k] / seen[k];
  }
  return out;
}

bool Robot::move(const Eigen::Vector2d& d) {
  ++moves_;
  const bool ok = arm_.move_relative(d.x(), d.y(), 0);
  if (ok) {
    travelled_ += d.norm();
    odometry_ += compass_vector(d);
    ++odometry_moves_;
  } else {
    ++refused_;
  }
  return ok;
}

std::vector<Neighbour> Robot::neighbours(int count, int reads) {
  const double h = config_.probe_mm;
  const Scan base = look(reads);
  last_scan_ = base;
  // Each probe goes out and back on its own, so a probe the arm refuses (at its limit) leaves the
  // robot where it was.
  const bool out_x = move({h, 0});
  const Scan px = out_x ? look(reads) : Scan{};
  if (out_x) move({-h, 0});
  const bool out_y = move({0, h});
  const Scan py = out_y ? look(reads) : Scan{};
  if (out_y) move({0, -h});
  std::vector<int> order;
  for (int k = 0; k < kSectors; ++k) {
    if (base[static_cast<std::size_t>(k)] > 0) order.push_back(k);
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double ra = base[static_cast<std::size_t>(a)];
    const double rb = base[static_cast<std::size_t>(b)];
    return ra != rb ? ra < rb : a < b;
  });
  std::vector<Neighbour> out;
  if (!out_x || !out_y) return out;  // at the arm's limit: no gradient
  for (const int k : order) {
    if (std::ssize(out) >= count) break;
    const double r = base[static_cast<std::size_t>(k)];
    // A range changes by at most h per probe; the sensor's error adds its bound on both looks.
    const double tolerance = 1.5 * h + 2.5 * config_.range_error * r / std::sqrt(std::max(1, config_.reads));
    const double rx = follow_range(px, k, r, tolerance);
    const double ry = follow_range(py, k, r, tolerance);
    if (rx == 0 || ry == 0) continue;
    Eigen::Vector2d g((rx - r) / h, (ry - r) / h);
    if (g.norm() < 0.2) continue;  // no usable gradient (noise, or a marble changing sectors)
    out.push_back({r, g.normalized(), k});
  }
  return out;
}

double Robot::read_heading() {
  double s = 0;
  double c = 0;
  const int n = std::max(1, config_.compass_reads);
  for (int i = 0; i < n; ++i) {
    const double h = compass_.read().heading_deg * kNxDegree;
    s += std::sin(h);
    c += std::cos(h);
  }
  heading_deg_ = std::atan2(s, c) / kNxDegree;
  return heading_deg_;
}

Eigen::Vector2d Robot::tool_direction(double compass_deg) const {
  const double a = (compass_deg - heading_deg_) * kNxDegree;
  return {std::cos(a), std::sin(a)};
}

Eigen::Vector2d Robot::compass_vector(const Eigen::Vector2d& tool_vector) const {
  const double a = heading_deg_ * kNxDegree;
  return {std::cos(a) * tool_vector.x() - std::sin(a) * tool_vector.y(),
          std::sin(a) * tool_vector.x() + std::cos(a) * tool_vector.y()};
}

double Robot::compass_heading(const Eigen::Vector2d& tool_direction) const {
  return wrap180(heading_deg_ + std::atan2(tool_direction.y(), tool_direction.x()) / kNxDegree);
}

}  // namespace neopipe::nav::nx
