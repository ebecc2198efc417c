// The recorder's lossy step against libjpeg (through OpenCV's imencode / imdecode at the same
// quality): the same image but for rare blocks where a coefficient on a quantisation boundary
// rounds the other way (float DCT here, libjpeg's integer one there), the loss growing as the
// quality falls.

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "rig_test_support.hpp"
#include "sim/jpeg_loss.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)

TEST(JpegLoss, IsWhatLibjpegDecodes) {
  sim::WorldRequest q;
  q.objects = 1000;
  q.seed = 3;
  const sim::World w = sim::generate_world(q);
  const sim::Rendering r = rig(sim::CameraKind::onboard);
  const auto cam = onboard(r, {250, 250, 0.2});
  cv::Mat frame = sim::SceneRenderer(r, cam).render(w.objects, 5, cam, 0);
  frame = frame(cv::Rect(0, 0, 251, 253)).clone();  // partial blocks at the right and bottom edges
  double previous = 0;
  for (const int quality : {95, 90, 75, 50, 20}) {
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(cv::imencode(".jpg", frame, bytes, {cv::IMWRITE_JPEG_QUALITY, quality}));
    const cv::Mat libjpeg = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
    const cv::Mat ours = sim::jpeg_loss(frame, quality);
    const double mean_diff = cv::norm(ours, libjpeg, cv::NORM_L1) / static_cast<double>(frame.total());
    cv::Mat diff;
    cv::absdiff(ours, libjpeg, diff);
    const double beyond_two = cv::countNonZero(diff > 2) / static_cast<double>(frame.total());
    const double loss = cv::norm(ours, frame, cv::NORM_L2) / std::sqrt(static_cast<double>(frame.total()));
    std::printf("quality %d: RMS loss %.2f gray levels; against libjpeg: mean %.3f, %.2f%% of pixels beyond 2\n",
                quality, loss, mean_diff, 100 * beyond_two);
    EXPECT_LT(mean_diff, 0.3) << quality;
    EXPECT_LT(beyond_two, 0.005) << quality;
    EXPECT_GT(loss, previous) << quality;
    previous = loss;
  }
  EXPECT_THROW((void)sim::jpeg_loss(frame, 0), std::invalid_argument);
}
