// The marble renderer against the truth it renders from: with noise off, the engine's blob graph
// finds every marble of a world in a global-camera frame and its intensity-weighted centroids sit
// on the projected centres (RMS <= 0.05 px); with noise the RMS grows but stays sub-pixel; the same
// seed gives the same pixels.

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"
#include "sim/camera_source.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/patch_blur.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace sim = neopipe::sim;
namespace pl = neopipe::pipeline;

namespace {

struct Match {
  int found = 0;      // truths with exactly one blob within 1 px
  int blobs = 0;      // blobs in the frame
  double rms_px = 0;  // of (wcx, wcy) - truth over the matched
  double max_px = 0;
};

// examples/marbles.yaml: blobs of (gray - 60), weighted by that excess.
Match measure(const cv::Mat& frame, const std::vector<sim::ProjectedMarble>& truth) {
  const auto graph = pl::load_graph_spec(std::string(NEOPIPE_EXAMPLES_DIR) + "/marbles.yaml");
  const auto results = pl::run_frames(pl::compile(graph, pl::standard_kernels()), {frame});
  const auto& blobs = std::get<pl::BlobList>(results.at(0).outputs.at(0));
  Match m;
  m.blobs = static_cast<int>(blobs.size());
  double sum2 = 0;
  for (const auto& t : truth) {
    int near = 0;
    double err = 0;
    for (const auto& b : blobs) {
      const double e = std::hypot(b.wcx - t.u, b.wcy - t.v);
      if (e < 1.0) {
        ++near;
        err = e;
      }
    }
    if (near == 1) {
      ++m.found;
      sum2 += err * err;
      m.max_px = std::max(m.max_px, err);
    }
  }
  m.rms_px = m.found > 0 ? std::sqrt(sum2 / m.found) : 0;
  return m;
}

sim::World test_world() {
  sim::WorldRequest q;
  q.objects = 400;
  q.seed = 7;
  return sim::generate_world(q);
}

}  // namespace

TEST(MarbleRenderer, NoiselessGlobalFrameGivesEveryMarbleWithinFiveHundredthsOfAPixel) {
  const sim::World world = test_world();
  const sim::PinholeCamera camera = sim::make_global_camera(world.size);
  sim::ImageModel model;
  model.noise_sigma = 0;
  const sim::MarbleRenderer renderer(model, camera.size());
  const cv::Mat frame = renderer.render(world.objects, world.marble_diameter, camera, 0);
  const auto truth = sim::visible_marbles(world.objects, camera);
  ASSERT_EQ(truth.size(), world.objects.size());  // the global camera sees the whole workspace
  const Match m = measure(frame, truth);
  EXPECT_EQ(m.blobs, static_cast<int>(world.objects.size()));
  EXPECT_EQ(m.found, static_cast<int>(world.objects.size()));
  EXPECT_LE(m.rms_px, 0.05);
  EXPECT_LE(m.max_px, 0.05);
  RecordProperty("rms_px", std::to_string(m.rms_px));
  std::printf("noise 0: rms %.4f px, max %.4f px\n", m.rms_px, m.max_px);
}

TEST(MarbleRenderer, NoiseSpreadsTheCentroidsButKeepsThemSubPixel) {
  const sim::World world = test_world();
  const sim::PinholeCamera camera = sim::make_global_camera(world.size);
  double previous = 0;
  for (const double sigma : {1.0, 2.0, 4.0}) {
    sim::ImageModel model;
    model.noise_sigma = sigma;
    const sim::MarbleRenderer renderer(model, camera.size());
    const cv::Mat frame = renderer.render(world.objects, world.marble_diameter, camera, 0);
    const Match m = measure(frame, sim::visible_marbles(world.objects, camera));
    std::printf("noise %.0f: rms %.4f px, max %.4f px, %d blobs\n", sigma, m.rms_px, m.max_px, m.blobs);
    EXPECT_EQ(m.found, static_cast<int>(world.objects.size())) << "sigma " << sigma;
    EXPECT_LT(m.rms_px, 0.1) << "sigma " << sigma;
    EXPECT_GT(m.rms_px, previous * 0.9) << "more noise should not make centroids better, sigma " << sigma;
    previous = m.rms_px;
  }
}

TEST(MarbleRenderer, SameSeedSamePixelsOtherSeedOrFrameOtherNoise) {
  const sim::World world = test_world();
  const auto camera = sim::make_onboard_camera({250, 250, 0.3});
  sim::ImageModel model;
  const sim::MarbleRenderer a(model, camera.size());
  const sim::MarbleRenderer b(model, camera.size());
  model.seed = 2;
  const sim::MarbleRenderer c(model, camera.size());
  const cv::Mat fa = a.render(world.objects, 5, camera, 4);
  EXPECT_EQ(cv::norm(fa, b.render(world.objects, 5, camera, 4), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(fa, c.render(world.objects, 5, camera, 4), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(fa, a.render(world.objects, 5, camera, 5), cv::NORM_INF), 0);
}

TEST(MarbleRenderer, NoiseHasTheConfiguredSigma) {
  // An empty, evenly lit workspace: every pixel is background + N(0, sigma), rounded. Over 65,536
  // pixels the sample sigma is within 1.5% of sqrt(sigma^2 + 1/12) (the rounding) with certainty
  // far beyond chance; a wrong sigma by 5% fails.
  sim::ImageModel model;
  model.gradient = 0;
  model.noise_sigma = 6;
  const auto camera = sim::make_onboard_camera({250, 250, 0});
  const sim::MarbleRenderer r(model, camera.size());
  const cv::Mat f = r.render({}, 5, camera, 0);
  cv::Scalar mean;
  cv::Scalar sd;
  cv::meanStdDev(f, mean, sd);
  EXPECT_NEAR(mean[0], 40, 0.1);
  EXPECT_NEAR(sd[0], std::sqrt(36 + 1.0 / 12), 0.015 * 6);
  // Neighbouring pixels and rows are independent.
  cv::Mat d;
  f.convertTo(d, CV_64F, 1, -mean[0]);
  const double right = d(cv::Rect(0, 0, 255, 256)).dot(d(cv::Rect(1, 0, 255, 256))) / (255 * 256 * sd[0] * sd[0]);
  const double down = d(cv::Rect(0, 0, 256, 255)).dot(d(cv::Rect(0, 1, 256, 255))) / (255 * 256 * sd[0] * sd[0]);
  EXPECT_LT(std::abs(right), 0.02);
  EXPECT_LT(std::abs(down), 0.02);
}

TEST(PixelCoverage, ExactForStraightEdges) {
  EXPECT_DOUBLE_EQ(sim::pixel_coverage(0, 1, 0), 0.5);
  EXPECT_DOUBLE_EQ(sim::pixel_coverage(0.25, 0, 1), 0.75);
  EXPECT_DOUBLE_EQ(sim::pixel_coverage(0.6, 1, 0), 1.0);
  EXPECT_DOUBLE_EQ(sim::pixel_coverage(-0.6, 1, 0), 0.0);
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(sim::pixel_coverage(0, h, h), 0.5, 1e-15);
  // A 45-degree edge a quarter diagonal in from a corner cuts off a right triangle with legs 1/2.
  EXPECT_NEAR(sim::pixel_coverage(-h / 2, h, h), 0.125, 1e-12);
  // Symmetry: what one side does not cover, the other does; and a Monte Carlo check at odd angles.
  sim::Random rng(5);
  for (int i = 0; i < 50; ++i) {
    const double a = rng.uniform(0, 6.283185307179586);
    const double s = rng.uniform(-0.8, 0.8);
    const double nx = std::cos(a);
    const double ny = std::sin(a);
    EXPECT_NEAR(sim::pixel_coverage(s, nx, ny) + sim::pixel_coverage(-s, -nx, -ny), 1.0, 1e-12);
    int in = 0;
    constexpr int kGrid = 400;
    for (int y = 0; y < kGrid; ++y) {
      for (int x = 0; x < kGrid; ++x) {
        const double px = (x + 0.5) / kGrid - 0.5;
        const double py = (y + 0.5) / kGrid - 0.5;
        in += (px * nx + py * ny < s) ? 1 : 0;
      }
    }
    EXPECT_NEAR(sim::pixel_coverage(s, nx, ny), static_cast<double>(in) / (kGrid * kGrid), 3e-3) << a << " " << s;
  }
}

TEST(PatchBlur, EqualsOpenCVSeparableFilterWithZerosAround) {
  const sim::PatchBlur blur(0.9);
  cv::Mat patch(23, 31, CV_32F);
  cv::randu(patch, 0, 100);
  cv::Mat expected;
  const cv::Mat k(blur.kernel(), true);
  cv::sepFilter2D(patch, expected, CV_32F, k, k, {-1, -1}, 0, cv::BORDER_CONSTANT);
  blur.apply(patch);
  EXPECT_LT(cv::norm(patch, expected, cv::NORM_INF), 1e-3);
  EXPECT_NEAR(cv::sum(cv::Mat(blur.kernel()))[0], 1.0, 1e-6);
}

TEST(SimCameraSource, GivesTheRenderersFramesAlongAPath) {
  const sim::World world = test_world();
  const std::vector<sim::Pose2> path{{100, 100, 0}, {120, 100, 0.1}, {140, 110, 0.2}};
  auto source = sim::onboard_path_source(world, {}, sim::ImageModel{}, path, neopipe::pipeline::io::ColorFormat::gray);
  EXPECT_EQ(source->frame_count(), 3);
  const sim::MarbleRenderer r(sim::ImageModel{}, {256, 256});
  for (std::int64_t i = 0; i < 3; ++i) {
    const auto f = source->next();
    ASSERT_TRUE(f);
    EXPECT_EQ(f->index, i);
    const auto expected =
        r.render(world.objects, world.marble_diameter, sim::make_onboard_camera(path[static_cast<std::size_t>(i)]), i);
    EXPECT_EQ(cv::norm(f->image, expected, cv::NORM_INF), 0);
  }
  EXPECT_FALSE(source->next());
  auto bgr = sim::onboard_path_source(world, {}, sim::ImageModel{}, path, neopipe::pipeline::io::ColorFormat::bgr);
  EXPECT_EQ(bgr->next()->image.type(), CV_8UC3);
}
