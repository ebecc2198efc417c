// Each effect of the rig's images, present where the geometry and optics say and gone when
// switched off: shading brighter towards the light, the highlight at the mirror point, the shadow
// away from the light with the area ray-tracing gives, the texture fixed to the world, vignetting,
// defocus growing to the corners, noise growing with the signal as the full well says, PRNU fixed
// from frame to frame, the table's light interpolated between nodes to a small fraction of a level.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "rig_test_support.hpp"
#include "sim/marble_truth.hpp"
#include "sim/shading.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The image direction (unit) in which world point `from` moves when it moves towards `to`.
Vector2d image_direction(const sim::PinholeCamera& cam, const Vector3d& from, const Vector3d& to) {
  const Vector3d step = from + 0.01 * (to - from).normalized();
  return (*cam.project(step) - *cam.project(from)).normalized();
}

double angle_deg(const Vector2d& a, const Vector2d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / std::numbers::pi;
}

// Pixels wholly inside the marble's outline: where the flat-lit render is the marble's albedo.
cv::Mat inside_mask(const sim::Rendering& r, const sim::PinholeCamera& cam, const sim::World& w) {
  sim::Rendering flat = r;
  flat.light.reset();
  flat.surfaces.table = 0;
  flat.surfaces.marble = 1;
  const cv::Mat cover = sim::SceneRenderer(flat, cam).radiance(w.objects, w.marble_diameter, cam);
  return cover > 0.9999F;
}

// A flat scene (no marbles, no light, no texture, no lens effects) of table albedo `level`.
cv::Mat flat_frame(sim::Rendering r, double level, std::int64_t frame) {
  r.light.reset();
  r.surfaces.texture = 0;
  r.surfaces.table = level;
  r.sensor.vignetting = 0;
  r.sensor.gradient = 0;
  const auto cam = onboard(r, {250, 250, 0});
  return sim::SceneRenderer(r, cam).render({}, 5, cam, frame);
}

}  // namespace

TEST(RigEffects, ShadingIsBrighterTowardsTheLight) {
  for (const auto kind : {sim::CameraKind::onboard, sim::CameraKind::global}) {
    sim::Rendering r = quiet(rig(kind));
    r.light->specular = 0;
    r.light->shadows = false;
    const sim::World w = one_marble({171.3, 122.8});
    const auto cam =
        kind == sim::CameraKind::onboard ? onboard(r, {170, 120, 0.5}) : sim::make_global_camera(w.size, {}, r);
    const cv::Mat inside = inside_mask(r, cam, w);
    const cv::Mat lit = sim::SceneRenderer(r, cam).radiance(w.objects, 5, cam);
    cv::Mat weights;
    lit.copyTo(weights, inside);
    cv::Mat ones;
    cv::Mat(inside / 255).convertTo(ones, CV_32F);
    const Vector2d offset = centroid(weights, {0, 0}) - centroid(ones, {0, 0});
    const Vector3d centre(171.3, 122.8, 2.5);
    const Vector2d towards = image_direction(cam, centre, r.light->position);
    std::printf("%s: brightness centroid %.3f px from the outline's, %.1f degrees from the light's direction\n",
                kind == sim::CameraKind::onboard ? "onboard" : "global", offset.norm(), angle_deg(offset, towards));
    EXPECT_GT(offset.norm(), 0.05);
    EXPECT_LT(angle_deg(offset, towards), 10);
    // Without the light: a flat disk of light, no offset.
    r.light.reset();
    cv::Mat flat;
    sim::SceneRenderer(r, cam).radiance(w.objects, 5, cam).copyTo(flat, inside);
    EXPECT_LT((centroid(flat, {0, 0}) - centroid(ones, {0, 0})).norm(), 1e-4);
  }
}

TEST(RigEffects, HighlightIsWhereTheMirrorReflectionIs) {
  // Ambient 1: the diffuse light is the same everywhere, so the brightest spot is the highlight.
  for (const auto kind : {sim::CameraKind::onboard, sim::CameraKind::global}) {
    sim::Rendering r = quiet(rig(kind));
    r.light->ambient = 1;
    r.light->specular = 100;
    r.light->shininess = 200;
    r.light->shadows = false;
    const Vector3d centre(312.4, 287.1, 2.5);
    const sim::World w = one_marble(centre.head<2>());
    const auto cam =
        kind == sim::CameraKind::onboard ? onboard(r, {305, 290, -0.3}) : sim::make_global_camera(w.size, {}, r);
    // The mirror point: its normal halves the directions to the light and to the camera.
    Vector3d n = ((r.light->position - centre).normalized() + (cam.centre() - centre).normalized()).normalized();
    for (int i = 0; i < 50; ++i) {
      const Vector3d x = centre + 2.5 * n;
      n = ((r.light->position - x).normalized() + (cam.centre() - x).normalized()).normalized();
    }
    const Vector2d predicted = *cam.project(centre + 2.5 * n);
    const cv::Mat excess = sim::SceneRenderer(r, cam).radiance(w.objects, 5, cam) - r.surfaces.marble;
    double peak = 0;
    cv::minMaxLoc(excess, nullptr, &peak);
    cv::Mat spot;  // the highlight's light, where it stands out
    excess.copyTo(spot, excess > 0.1 * peak);
    const Vector2d found = centroid(spot, {0, 0});
    std::printf("%s highlight: peak +%.1f gray levels, %.3f px from the mirror point\n",
                kind == sim::CameraKind::onboard ? "onboard" : "global", peak, (found - predicted).norm());
    EXPECT_GT(peak, 0.3 * r.light->specular);  // a spot about a pixel wide is averaged over its pixel
    EXPECT_LT((found - predicted).norm(), 0.25);
    r.light->specular = 0;
    double none = 0;
    cv::minMaxLoc(sim::SceneRenderer(r, cam).radiance(w.objects, 5, cam), nullptr, &none);
    EXPECT_LE(none, r.surfaces.marble + 1e-3);
  }
}

TEST(RigEffects, ShadowFallsAwayFromTheLightWithTheAreaRayTracingGives) {
  for (const bool harsh : {false, true}) {
    sim::Rendering r =
        quiet(sim::rendering_for(harsh ? sim::Realism::harsh : sim::Realism::rig, sim::CameraKind::onboard));
    r.light->specular = 0;
    const Vector3d centre(380.2, 141.7, 2.5);
    const sim::World w = one_marble(centre.head<2>());
    const auto cam = onboard(r, {380, 140, 0.2});
    const cv::Mat with = sim::SceneRenderer(r, cam).radiance(w.objects, 5, cam);
    sim::Rendering no_shadows = r;
    no_shadows.light->shadows = false;
    const cv::Mat without = sim::SceneRenderer(no_shadows, cam).radiance(w.objects, 5, cam);
    const cv::Mat darker = without - with;  // >= 0, in the shadow
    const Vector2d contact = *cam.project({centre.x(), centre.y(), 0});
    const Vector2d away =
        -image_direction(cam, {centre.x(), centre.y(), 0}, {r.light->position.x(), r.light->position.y(), 0});
    const Vector2d where = centroid(darker, {0, 0}) - contact;
    // The shadowed fraction of each pixel: the loss over the table's direct light there.
    const sim::Shader shader(*r.light, r.light->position, r.light->position.z());
    double area = 0;
    cv::Mat box_points;
    cv::findNonZero(darker > 1e-4F, box_points);
    const cv::Rect box = cv::boundingRect(box_points) + cv::Size(2, 2) - cv::Point(1, 1);
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        const auto p = cam.plane_point({x, y});
        const double direct = r.surfaces.table * (1 - r.light->ambient) * shader.table_direct({p->x(), p->y(), 0});
        area += darker.at<float>(y, x) / direct;
      }
    }
    // Ray tracing, 16 x 16 rays a pixel: a ray that misses the marble and meets the table where the
    // marble hides the light.
    double traced = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        for (int sy = 0; sy < 16; ++sy) {
          for (int sx = 0; sx < 16; ++sx) {
            const double u = x - 0.5 + (sx + 0.5) / 16;
            const double v = y - 0.5 + (sy + 0.5) / 16;
            if (ray_hits(cam.centre(), ray_through(cam, u, v), centre, 2.5)) continue;
            const auto p = cam.plane_point({u, v});
            const Vector3d table(p->x(), p->y(), 0);
            if (ray_hits(table, r.light->position - table, centre, 2.5)) traced += 1.0 / 256;
          }
        }
      }
    }
    std::printf(
        "%s: shadow %.2f px from the contact point, %.1f degrees from away-from-the-light; visible area "
        "%.2f px^2, ray-traced %.2f px^2\n",
        harsh ? "harsh" : "rig", where.norm(), angle_deg(where, away), area, traced);
    EXPECT_LT(angle_deg(where, away), 15);
    EXPECT_GT(traced, 10);
    EXPECT_NEAR(area, traced, 0.02 * traced + 0.5);
  }
}

TEST(RigEffects, TextureIsFixedToTheWorld) {
  sim::Rendering r = quiet(rig(sim::CameraKind::onboard));
  r.light.reset();
  r.surfaces.texture = 0.05;
  r.lens = {};  // a shift of the camera is then a shift of the image
  const sim::OnboardCameraConfig config = sim::onboard_config_for(r, 5);
  const double mm_per_px =
      (config.window_plane_z + config.height) / (config.side_px / config.window_mm * config.height);
  const auto here = sim::make_onboard_camera({250, 250, 0}, config, r);
  const auto there = sim::make_onboard_camera({250 + 16 * mm_per_px, 250, 0}, config, r);  // 16 px East
  const sim::SceneRenderer renderer(r, here);
  ASSERT_EQ(16 % renderer.table_spacing(), 0);  // the shift moves whole nodes
  const cv::Mat a = renderer.radiance({}, 5, here);
  const cv::Mat b = renderer.radiance({}, 5, there);
  const cv::Rect left(0, 0, 240, 256);
  const double moved = cv::norm(a(left + cv::Point(16, 0)), b(left), cv::NORM_INF);
  const double unmoved = cv::norm(a(left), b(left), cv::NORM_INF);
  cv::Scalar mean;
  cv::Scalar sd;
  cv::meanStdDev(a, mean, sd);
  std::printf("texture: sd %.2f gray levels; shifted with the world %.5f, in place %.2f (max difference)\n", sd[0],
              moved, unmoved);
  EXPECT_GT(sd[0], 0.5);
  EXPECT_LT(moved, 1e-3);
  EXPECT_GT(unmoved, 1);
  r.surfaces.texture = 0;
  cv::meanStdDev(sim::SceneRenderer(r, here).radiance({}, 5, here), mean, sd);
  EXPECT_LT(sd[0], 1e-4);
}

TEST(RigEffects, TableLightBetweenNodesIsWithinATenthOfTheTexturesAmplitude) {
  for (const auto kind : {sim::CameraKind::onboard, sim::CameraKind::global}) {
    const sim::Rendering r = quiet(sim::rendering_for(sim::Realism::harsh, kind));
    sim::Rendering textured = r;
    textured.surfaces.texture = 0.1;
    const auto cam =
        kind == sim::CameraKind::onboard ? onboard(r, {123, 321, 0.8}) : sim::make_global_camera({500, 500}, {}, r);
    const sim::SceneRenderer renderer(textured, cam);
    const cv::Mat field = renderer.radiance({}, 5, cam);
    const sim::Shader shader(*r.light, r.light->position, r.light->position.z());
    double worst = 0;
    for (int y = 0; y < field.rows; y += 7) {
      for (int x = 0; x < field.cols; x += 5) {
        const auto p = cam.plane_point({x, y});
        const double exact = textured.surfaces.table *
                             (1 + 0.1 * renderer.texture()(static_cast<float>(p->x()), static_cast<float>(p->y()))) *
                             shader.lit(shader.table_direct({p->x(), p->y(), 0}));
        worst = std::max(worst, std::abs(field.at<float>(y, x) - exact));
      }
    }
    const double amplitude = textured.surfaces.table * 0.1;
    std::printf("%s table light, nodes %d px apart: worst %.3f gray levels from exact (texture +-%.0f)\n",
                kind == sim::CameraKind::onboard ? "onboard" : "global", renderer.table_spacing(), worst, amplitude);
    EXPECT_LT(worst, 0.1 * amplitude);
  }
}

TEST(RigEffects, VignettingDarkensTheCornersByItsFraction) {
  sim::Rendering r = quiet(rig(sim::CameraKind::onboard));
  r.light.reset();
  r.surfaces.table = 200;
  r.sensor.vignetting = 0.2;
  const auto cam = onboard(r, {250, 250, 0});
  const sim::SceneRenderer renderer(r, cam);
  const cv::Mat f = renderer.render({}, 5, cam, 0);
  const cv::Mat& gain = renderer.sensor().gain();
  // The corner pixel's centre is 0.5 px inside the corner: (1 - 0.2 rho^2) there.
  const double rho2 = 2 * 127.5 * 127.5 / (2 * 128.0 * 128.0);
  EXPECT_NEAR(gain.at<float>(0, 0), 1 - 0.2 * rho2, 1e-6);
  EXPECT_NEAR(gain.at<float>(255, 0), 1 - 0.2 * rho2, 1e-6);
  const double ratio = f.at<std::uint8_t>(0, 0) / static_cast<double>(f.at<std::uint8_t>(128, 128));
  std::printf("vignetting 0.2: corner / centre %.3f\n", ratio);
  EXPECT_NEAR(ratio, 1 - 0.2 * rho2, 0.005);
  r.sensor.vignetting = 0;
  const cv::Mat none = sim::SceneRenderer(r, cam).render({}, 5, cam, 0);
  EXPECT_EQ(none.at<std::uint8_t>(0, 0), none.at<std::uint8_t>(128, 128));
}

TEST(RigEffects, DefocusIsSharperAtTheCentreThanAtACorner) {
  // Each marble's light is blurred with the sigma at its place: the sharp light blurred by OpenCV
  // with that sigma is the same image; and an outline's steepest slope falls towards the corners.
  sim::Rendering r = quiet(rig(sim::CameraKind::onboard));
  r.light.reset();
  sim::Rendering blurred = r;
  blurred.defocus = {0.8, 2.0};
  const auto cam = onboard(r, {250, 250, 0});
  const sim::SceneRenderer sharp(r, cam);
  const sim::SceneRenderer lens(blurred, cam);
  std::vector<double> slopes;
  for (const Vector2d& at : {Vector2d(250, 250), Vector2d(270, 230)}) {
    const sim::World w = one_marble(at);
    const auto px = *cam.project({at.x(), at.y(), 2.5});
    const double sigma = lens.defocus().sigma(px.x(), px.y());
    cv::Mat expected;
    cv::GaussianBlur(sharp.radiance(w.objects, 5, cam), expected, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
    const cv::Mat got = lens.radiance(w.objects, 5, cam);
    const double worst = cv::norm(got, expected, cv::NORM_INF);
    cv::Mat gx;
    cv::Sobel(got, gx, CV_32F, 1, 0, 3);
    double steepest = 0;
    cv::minMaxLoc(cv::abs(gx), nullptr, &steepest);
    slopes.push_back(steepest);
    std::printf("defocus at (%.0f, %.0f) px: sigma %.2f; against OpenCV's blur %.3f gray levels; steepest slope %.1f\n",
                px.x(), px.y(), sigma, worst, steepest);
    // The bank's kernels are 0.02 px of sigma apart: up to 0.01 px off, ~0.5% of a 170-level edge.
    EXPECT_LT(worst, 1.0);
  }
  EXPECT_GT(slopes[0], 1.3 * slopes[1]);
}

TEST(RigEffects, NoiseVarianceGrowsWithTheSignalAsTheFullWellSays) {
  sim::Rendering r = rig(sim::CameraKind::onboard);
  r.sensor.prnu = 0;
  r.sensor.read_noise = 1.5;
  r.sensor.full_well = 12000.0;
  for (const double level : {40.0, 160.0}) {
    cv::Scalar mean;
    cv::Scalar sd;
    cv::meanStdDev(flat_frame(r, level, 3), mean, sd);
    const double expected = 1.5 * 1.5 + level * 255 / 12000 + 1.0 / 12;  // read, shot, rounding
    std::printf("level %.0f: variance %.3f, read + shot + rounding %.3f\n", level, sd[0] * sd[0], expected);
    EXPECT_NEAR(mean[0], level, 0.05);
    EXPECT_NEAR(sd[0] * sd[0], expected, 0.04 * expected);
  }
  r.sensor.full_well.reset();
  cv::Scalar mean;
  cv::Scalar sd;
  cv::meanStdDev(flat_frame(r, 160, 3), mean, sd);
  EXPECT_NEAR(sd[0] * sd[0], 1.5 * 1.5 + 1.0 / 12, 0.04 * 2.33);
}

TEST(RigEffects, PrnuIsFixedFromFrameToFrame) {
  // PRNU alone, for the sensor seeded by `seed`.
  const auto prnu_only = [](std::uint64_t seed) {
    sim::Rendering r = rig(sim::CameraKind::onboard);
    r.sensor.read_noise = 0;
    r.sensor.full_well.reset();
    r.sensor.prnu = 0.02;
    r.sensor.seed = seed;
    return r;
  };
  const sim::Rendering r = prnu_only(1);
  const cv::Mat a = flat_frame(r, 160, 0);
  EXPECT_EQ(cv::norm(a, flat_frame(r, 160, 9), cv::NORM_INF), 0);  // the same pattern every frame
  cv::Scalar mean;
  cv::Scalar sd;
  cv::meanStdDev(a, mean, sd);
  EXPECT_NEAR(sd[0], std::sqrt(std::pow(0.02 * 160, 2) + 1.0 / 12), 0.1);
  const sim::Rendering other = prnu_only(9);
  cv::Mat fa;
  cv::Mat fb;
  a.convertTo(fa, CV_32F, 1, -mean[0]);
  flat_frame(other, 160, 0).convertTo(fb, CV_32F, 1, -mean[0]);
  EXPECT_LT(std::abs(fa.dot(fb)) / (cv::norm(fa) * cv::norm(fb)), 0.05);  // another camera, another pattern
  // Under noise, averages of different frames agree on the pattern.
  sim::Rendering noisy = prnu_only(1);
  noisy.sensor.read_noise = 1.5;
  noisy.sensor.full_well = 12000.0;
  cv::Mat first = cv::Mat::zeros(256, 256, CV_32F);
  cv::Mat second = cv::Mat::zeros(256, 256, CV_32F);
  for (int f = 0; f < 16; ++f) {
    cv::accumulate(flat_frame(noisy, 160, f), first);
    cv::accumulate(flat_frame(noisy, 160, 16 + f), second);
  }
  first -= cv::mean(first);
  second -= cv::mean(second);
  const double correlation = first.dot(second) / (cv::norm(first) * cv::norm(second));
  std::printf("PRNU under noise: averages of 16 frames correlate %.3f\n", correlation);
  EXPECT_GT(correlation, 0.8);
}
