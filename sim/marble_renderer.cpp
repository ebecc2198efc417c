#include "sim/marble_renderer.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

namespace neopipe::sim {
namespace {

// Brightness of the dome at normalised radius rho (< 1), as a fraction of the centre's excess.
double dome(double rho2, double rim) {
  return rim + (1 - rim) * std::sqrt(std::max(0.0, 1 - rho2));
}

}  // namespace

double pixel_coverage(double s, double nx, double ny) {
  double a = std::abs(nx);
  double b = std::abs(ny);
  if (a < b) std::swap(a, b);
  const double t = s + (a + b) / 2;  // how far the edge has swept in from the pixel's far corner
  if (t <= 0) return 0;
  if (t >= a + b) return 1;
  if (b < 1e-9) return std::min(t / a, 1.0);
  if (t < b) return t * t / (2 * a * b);
  if (t <= a) return (t - b / 2) / a;
  const double u = a + b - t;
  return 1 - u * u / (2 * a * b);
}

namespace {

// A box on the plane holding every marble that can touch the image (the image corners and edge
// midpoints mapped to the plane, grown by a quarter for the bulge of distortion and by a marble),
// or nothing when the camera sees the horizon. Saves projecting every marble of a big world for a
// small onboard window.
std::optional<Eigen::AlignedBox2d> footprint(const PinholeCamera& camera, double diameter) {
  const double w = camera.size().width - 0.5;
  const double h = camera.size().height - 0.5;
  Eigen::AlignedBox2d box;
  for (const double u : {-0.5, w / 2, w}) {
    for (const double v : {-0.5, h / 2, h}) {
      const auto p = camera.plane_point({u, v});
      if (!p) return std::nullopt;
      box.extend(*p);
    }
  }
  const Eigen::Vector2d grow = box.sizes() / 4 + Eigen::Vector2d::Constant(diameter);
  return Eigen::AlignedBox2d(box.min() - grow, box.max() + grow);
}

}  // namespace

MarbleRenderer::MarbleRenderer(const ImageModel& model, cv::Size size)
    : model_(model), size_(size), gain_(size, CV_32F), noise_(model.seed) {
  if (model.blur_sigma > 0) blur_.emplace(model.blur_sigma);
  if (size.width > GaussianNoise::kRowMax) throw std::invalid_argument("image wider than the noise table's rows");
  const double a = model.gradient_angle_deg * std::numbers::pi / 180;
  const double half_diagonal = std::hypot(size.width, size.height) / 2;
  const double cx = (size.width - 1) / 2.0;
  const double cy = (size.height - 1) / 2.0;
  for (int y = 0; y < size.height; ++y) {
    auto* g = gain_.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const double along = ((x - cx) * std::cos(a) + (y - cy) * std::sin(a)) / half_diagonal;
      g[x] = static_cast<float>(1 + model.gradient * along);
    }
  }
}

void MarbleRenderer::splat(const Eigen::Vector2d& centre, double radius, const PinholeCamera& camera,
                           cv::Mat& excess) const {
  const auto c = camera.project({centre.x(), centre.y(), 0});
  if (!c) return;
  const Eigen::Matrix2d j = camera.plane_jacobian(centre);
  if (std::abs(j.determinant()) < 1e-12) return;
  const Eigen::Matrix2d to_disk = j.inverse() / radius;  // pixel offset -> offset in marble radii
  // The disk's image is the ellipse |to_disk * d| <= 1; its half extents along u and v:
  const Eigen::Matrix2d m = j * j.transpose();
  const double ext_u = radius * std::sqrt(m(0, 0));
  const double ext_v = radius * std::sqrt(m(1, 1));
  const double pad = 1 + (blur_ ? blur_->radius() : 0);
  const int x0 = static_cast<int>(std::floor(c->x() - ext_u - pad));
  const int x1 = static_cast<int>(std::ceil(c->x() + ext_u + pad));
  const int y0 = static_cast<int>(std::floor(c->y() - ext_v - pad));
  const int y1 = static_cast<int>(std::ceil(c->y() + ext_v + pad));
  const cv::Rect patch_rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  const cv::Rect visible = patch_rect & cv::Rect({0, 0}, excess.size());
  if (visible.empty()) return;

  // How far (in marble radii) any point of a pixel can be from its centre: decides interior, rim, or
  // outside without sampling.
  const double half_pixel =
      std::max((to_disk * Eigen::Vector2d(0.5, 0.5)).norm(), (to_disk * Eigen::Vector2d(0.5, -0.5)).norm());
  const double peak = model_.marble - model_.background;
  const double inner2 = half_pixel < 1 ? (1 - half_pixel) * (1 - half_pixel) : -1;  // rho^2 below: interior
  const double outer2 = (1 + half_pixel) * (1 + half_pixel);                        // rho^2 above: outside
  const Eigen::Vector2d step = to_disk.col(0);  // d moves by this from one pixel to the next in a row
  cv::Mat patch = cv::Mat::zeros(patch_rect.size(), CV_32F);
  for (int y = y0; y <= y1; ++y) {
    auto* row = patch.ptr<float>(y - y0);
    // rho^2 along the row is a quadratic in x; visit only where it is below outer2.
    const Eigen::Vector2d d0 = to_disk * Eigen::Vector2d(x0 - c->x(), y - c->y());
    const double qa = step.squaredNorm();
    const double qb = d0.dot(step);
    const double disc = qb * qb - qa * (d0.squaredNorm() - outer2);
    if (disc <= 0) continue;
    const double root = std::sqrt(disc);
    const int first = std::max(0, static_cast<int>(std::floor((-qb - root) / qa)));
    const int last = std::min(x1 - x0, static_cast<int>(std::ceil((-qb + root) / qa)));
    Eigen::Vector2d d = d0 + first * step;
    for (int x = x0 + first; x <= x0 + last; ++x, d += step) {
      const double rho2 = d.squaredNorm();
      if (rho2 >= outer2) continue;
      double value = 0;
      if (rho2 < inner2) {
        value = dome(rho2, model_.rim);
      } else {
        // The rim crosses this pixel: its exact area behind the rim's tangent line (the rim is many
        // pixels across, so the line is the rim to well under 1% of a pixel's area), times the dome
        // halfway into the covered part.
        const double rho = std::sqrt(rho2);
        const Eigen::Vector2d grad = to_disk.transpose() * d / std::max(rho, 1e-12);  // d(rho)/d(pixel)
        const double g = grad.norm();
        const double cover = pixel_coverage((1 - rho) / g, grad.x() / g, grad.y() / g);
        const double inside = std::max(0.0, 1 - 0.5 * cover * g);
        value = cover * dome(inside * inside, model_.rim);
      }
      row[x - x0] = static_cast<float>(peak * value);
    }
  }
  if (model_.blur_sigma > 0) {
    // The patch reaches the kernel's radius past the rim, so blurring it alone with zeros outside equals
    // blurring the whole frame's excess.
    blur_->apply(patch);
  }
  excess(visible) += patch(visible - patch_rect.tl());
}

cv::Mat MarbleRenderer::finish(const cv::Mat& excess, std::int64_t frame) const {
  cv::Mat out(size_, CV_8U);
  cv::Mat light(1, size_.width, CV_32F);  // one row of light before quantisation
  Random rows = frame_random(model_.seed, frame);
  const auto bg = static_cast<float>(model_.background);
  const auto sigma = static_cast<float>(model_.noise_sigma);
  auto* l = light.ptr<float>();
  for (int y = 0; y < size_.height; ++y) {
    const auto* e = excess.ptr<float>(y);
    const auto* g = gain_.ptr<float>(y);
    // Plain arithmetic loops the compiler vectorises; OpenCV's convertTo rounds and saturates.
    if (sigma > 0) {
      const float* n = noise_.row(rows, size_.width).data();
      for (int x = 0; x < size_.width; ++x) l[x] = g[x] * (bg + e[x]) + sigma * n[x];
    } else {
      for (int x = 0; x < size_.width; ++x) l[x] = g[x] * (bg + e[x]);
    }
    cv::Mat dst = out.row(y);
    light.convertTo(dst, CV_8U);
  }
  return out;
}

cv::Mat MarbleRenderer::render(std::span<const Eigen::Vector2d> centres, double diameter, const PinholeCamera& camera,
                               std::int64_t frame) const {
  if (camera.size() != size_) throw std::invalid_argument("camera image size differs from the renderer's");
  cv::Mat excess = cv::Mat::zeros(size_, CV_32F);
  const auto seen = footprint(camera, diameter);
  for (const auto& p : centres) {
    if (seen && !seen->contains(p)) continue;
    splat(p, diameter / 2, camera, excess);
  }
  return finish(excess, frame);
}

cv::Mat MarbleRenderer::expose(const cv::Mat& light, std::int64_t frame) const {
  if (light.size() != size_ || light.type() != CV_32F)
    throw std::invalid_argument("light image of the wrong size or type");
  cv::Mat excess = light - model_.background;
  if (model_.blur_sigma > 0) {
    cv::GaussianBlur(excess, excess, cv::Size(0, 0), model_.blur_sigma, model_.blur_sigma, cv::BORDER_REPLICATE);
  }
  return finish(excess, frame);
}

std::vector<ProjectedMarble> visible_marbles(std::span<const Eigen::Vector2d> centres, const PinholeCamera& camera) {
  std::vector<ProjectedMarble> out;
  const cv::Size s = camera.size();
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const auto c = camera.project({centres[i].x(), centres[i].y(), 0});
    if (c && c->x() > -0.5 && c->y() > -0.5 && c->x() < s.width - 0.5 && c->y() < s.height - 0.5) {
      out.push_back({static_cast<int>(i), c->x(), c->y()});
    }
  }
  return out;
}

}  // namespace neopipe::sim
