// Linked into the suites that run under -fsanitize=thread (tests/CMakeLists.txt), and only there.
//
// OpenCV's own parallel loops (cv::GaussianBlur, cv::resize, ... in the tests and in the readers) run
// on oneTBB through TBB's inline task code compiled into Debian's libopencv_core, which is not built
// with TSan. The worker's release of a finished loop is therefore invisible, and TSan reports the
// next use of the stack memory that held the loop's task_group_context as a race with the worker,
// far from any OpenCV frame (so no suppression can name it). Running OpenCV's loops on the calling
// thread removes those false reports; neopipe's own threads (the executor's stripes and groups, the
// trials' parallel journeys) still run on the instrumented oneTBB, as in a normal build.
#include <gtest/gtest.h>

#include <opencv2/core/utility.hpp>

namespace {

class OpenCvOnCallingThread : public ::testing::Environment {
 public:
  void SetUp() override { cv::setNumThreads(1); }
};

// gtest_main's main() runs the tests after static initialisation, so registering here reaches it.
// GoogleTest takes ownership of the environment (its API takes a raw pointer).
[[maybe_unused]] ::testing::Environment* const environment =
    ::testing::AddGlobalTestEnvironment(new OpenCvOnCallingThread);  // NOLINT(cppcoreguidelines-owning-memory)

}  // namespace
