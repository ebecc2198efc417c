// Under the rig preset every marble stays easy to segment on both cameras: its whole outline is
// clearly brighter than the table and the shadows (before noise), and the engine's blob graph finds
// one blob per marble with a fixed threshold or with Otsu's, the highlight inside it.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "rig_test_support.hpp"
#include "sim/marble_truth.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)

namespace {

// The frame's signal before the lens blurs it and the sensor adds noise (light through vignetting
// and PRNU), and which pixels lie wholly inside a marble's outline or wholly outside every one.
struct Signal {
  cv::Mat signal;
  cv::Mat inside;
  cv::Mat outside;
};

Signal signal_of(sim::Rendering r, const sim::PinholeCamera& cam, const sim::World& w) {
  r.defocus = {0, 0};
  const sim::SceneRenderer renderer(r, cam);
  sim::Rendering flat = quiet(r);
  flat.light.reset();
  flat.surfaces.table = 0;
  flat.surfaces.marble = 1;
  const cv::Mat cover = sim::SceneRenderer(flat, cam).radiance(w.objects, w.marble_diameter, cam);
  Signal s;
  cv::multiply(renderer.radiance(w.objects, w.marble_diameter, cam), renderer.sensor().gain(), s.signal);
  s.inside = cover > 0.9999F;
  s.outside = cover <= 0.0F;
  return s;
}

// How many blobs lie within a radius of each truth, and how many big blobs lie near none.
struct Count {
  int marbles = 0;
  int single = 0;  // marbles with exactly one blob
  int strays = 0;  // blobs of 20 px or more near no marble
};

Count count(const pl::BlobList& found, const std::vector<sim::MarbleTruth>& truth,
            const std::vector<Eigen::Vector2d>& all, const sim::PinholeCamera& cam, double radius_px) {
  Count c;
  for (const auto& t : truth) {
    int near = 0;
    for (const auto& b : found) near += std::hypot(b.cx - t.u, b.cy - t.v) < radius_px ? 1 : 0;
    ++c.marbles;
    c.single += near == 1 ? 1 : 0;
  }
  for (const auto& b : found) {
    if (b.area < 20) continue;
    bool marble = false;
    for (const auto& p : all) {
      const auto px = cam.project({p.x(), p.y(), 2.5});
      marble = marble || (px && std::hypot(b.cx - px->x(), b.cy - px->y()) < 2 * radius_px);
    }
    c.strays += marble ? 0 : 1;
  }
  return c;
}

}  // namespace

TEST(RigSegmentation, EveryOutlineIsClearlyBrighterThanTheTableAndItsShadows) {
  const sim::World w = world(400, 7);
  for (const auto kind : {sim::CameraKind::global, sim::CameraKind::onboard}) {
    const sim::Rendering r = rig(kind);
    std::vector<sim::PinholeCamera> cameras;
    if (kind == sim::CameraKind::global) {
      cameras.push_back(sim::make_global_camera(w.size, {}, r));
    } else {
      for (const auto& p : {w.objects[0], w.objects[17], w.objects[123], w.objects[301]}) {
        cameras.push_back(onboard(r, {p.x() + 7, p.y() - 5, 0.4}));
      }
    }
    double darkest_marble = 1e9;
    double brightest_table = 0;
    for (const auto& cam : cameras) {
      const Signal s = signal_of(r, cam, w);
      double lo = 0;
      double hi = 0;
      cv::minMaxLoc(s.signal, &lo, nullptr, nullptr, nullptr, s.inside);
      cv::minMaxLoc(s.signal, nullptr, &hi, nullptr, nullptr, s.outside);
      darkest_marble = std::min(darkest_marble, lo);
      brightest_table = std::max(brightest_table, hi);
    }
    std::printf("%s: darkest marble pixel %.1f, brightest table pixel %.1f (gray levels before noise)\n",
                kind == sim::CameraKind::global ? "global" : "onboard", darkest_marble, brightest_table);
    EXPECT_GT(darkest_marble, 1.5 * brightest_table);
    EXPECT_GT(darkest_marble - brightest_table, 25);  // over 10 sigma of the noise there
  }
}

TEST(RigSegmentation, OneBlobPerMarbleOnTheGlobalCamera) {
  for (const auto& w : {world(400, 7), world(100, 1)}) {
    const sim::Rendering r = rig(sim::CameraKind::global);
    const auto cam = sim::make_global_camera(w.size, {}, r);
    const cv::Mat frame = sim::SceneRenderer(r, cam).render(w.objects, w.marble_diameter, cam, 0);
    const auto truth = sim::marble_truth(w.objects, w.marble_diameter, cam);
    for (const std::optional<int> threshold : {std::optional<int>(60), std::optional<int>(), std::optional<int>(150)}) {
      const auto found = blobs(frame, threshold);
      const Count c = count(found, truth, w.objects, cam, 4);
      std::printf("global, %zu marbles, threshold %s: %zu blobs, %d of %d marbles one blob each, %d strays\n",
                  w.objects.size(), threshold ? std::to_string(*threshold).c_str() : "Otsu", found.size(), c.single,
                  c.marbles, c.strays);
      EXPECT_EQ(c.single, c.marbles);
      EXPECT_EQ(c.strays, 0);
      if (threshold != 150) {
        EXPECT_EQ(found.size(), w.objects.size());
      }
    }
  }
}

TEST(RigSegmentation, OneBlobPerMarbleOnTheOnboardCamera) {
  for (const auto& w : {world(100, 1), world(1000, 3)}) {
    const sim::Rendering r = rig(sim::CameraKind::onboard);
    const sim::SceneRenderer renderer(r, onboard(r, {250, 250, 0}));
    Count otsu;
    Count fixed;
    int frames = 0;
    for (int i = 0; i < 200; ++i) {
      const double t = i * 0.0314;
      const auto cam = onboard(r, {250 + 180 * std::cos(3 * t), 250 + 180 * std::sin(2 * t), t});
      // Marbles whose outline is wholly in view.
      std::vector<sim::MarbleTruth> whole;
      for (const auto& m : sim::marble_truth(w.objects, w.marble_diameter, cam)) {
        if (m.u > 15 && m.v > 15 && m.u < 240 && m.v < 240) whole.push_back(m);
      }
      if (whole.empty()) continue;  // Otsu splits the noise of an empty view, as the navigator knows
      ++frames;
      const cv::Mat frame = renderer.render(w.objects, w.marble_diameter, cam, i);
      for (auto [threshold, total] :
           {std::pair{std::optional<int>(), &otsu}, std::pair{std::optional<int>(60), &fixed}}) {
        const Count c = count(blobs(frame, threshold), whole, w.objects, cam, 10);
        total->marbles += c.marbles;
        total->single += c.single;
        total->strays += c.strays;
      }
    }
    std::printf(
        "onboard, %zu marbles, %d frames: Otsu %d of %d marbles one blob each (%d strays); threshold 60 %d "
        "of %d (%d strays)\n",
        w.objects.size(), frames, otsu.single, otsu.marbles, otsu.strays, fixed.single, fixed.marbles, fixed.strays);
    EXPECT_GT(frames, 20);
    EXPECT_EQ(otsu.single, otsu.marbles);
    EXPECT_EQ(otsu.strays, 0);
    EXPECT_EQ(fixed.single, fixed.marbles);
    EXPECT_EQ(fixed.strays, 0);
  }
}
