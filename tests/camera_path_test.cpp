#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "cli_options.h"

namespace raybudget {
namespace {

Camera testStart() {
  Camera start;
  start.position = {3.0f, 2.0f, 4.0f};
  start.target = {1.0f, 0.5f, -1.0f};
  return start;
}

float apart(const Camera& a, const Camera& b) { return glm::length(a.position - b.position) + glm::length(a.target - b.target); }

// The benchmark's lead-in (sweep --lead-in): the cameras before a recorded frame lie on its
// path, a hundredth of the frames' spacing apart, ending one step before the frame itself.
TEST(CameraPath, ApproachingAFrameStepsAlongItsPathAndArrivesAtIt) {
  const Camera start = testStart();
  for (const char* path : {"orbit", "flythrough"}) {
    SCOPED_TRACE(path);
    for (uint32_t frame = 1; frame < 3; ++frame) {
      const Camera at = cli::cameraOnPath(path, start, frame, 3);
      EXPECT_EQ(apart(cli::cameraApproaching(path, start, frame, 3, 0), at), 0.0f) << "no steps back: the frame itself";
      EXPECT_EQ(apart(cli::cameraApproaching(path, start, frame, 3, 100), cli::cameraOnPath(path, start, frame - 1, 3)), 0.0f)
          << "a hundred steps back: the frame before";
      // Each step back lies further from the frame, by about the same length.
      float previous = 0.0f, first = apart(cli::cameraApproaching(path, start, frame, 3, 1), at);
      EXPECT_GT(first, 0.0f);
      for (uint32_t back = 1; back <= 8; ++back) {
        const float d = apart(cli::cameraApproaching(path, start, frame, 3, back), at);
        EXPECT_GT(d, previous);
        EXPECT_LT(d, 1.5f * back * first);
        previous = d;
      }
    }
  }
}

TEST(CameraPath, ApproachingTheFirstFrameWrapsRoundAnOrbitAndStopsAtAFlythroughsStart) {
  const Camera start = testStart();
  EXPECT_LT(apart(cli::cameraApproaching("orbit", start, 0, 3, 100), cli::cameraOnPath("orbit", start, 2, 3)), 1e-4f);
  EXPECT_EQ(apart(cli::cameraApproaching("flythrough", start, 0, 3, 5), cli::cameraOnPath("flythrough", start, 0, 3)), 0.0f);
}

}  // namespace
}  // namespace raybudget
