#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "raybudget/camera.h"
#include "raybudget/scene.h"
#include "support/procedural.h"

namespace raybudget {
namespace {

TEST(Camera, OrbitKeepsHeightAndDistanceAndClosesTheCircle) {
  Camera start;
  start.position = {3.0f, 2.0f, 4.0f};
  start.target = {1.0f, 0.5f, -1.0f};
  const float radius = glm::length(glm::vec2(start.position.x - start.target.x, start.position.z - start.target.z));
  for (uint32_t f = 0; f < 16; ++f) {
    const Camera c = orbitCamera(start, f, 16);
    EXPECT_NEAR(c.position.y, start.position.y, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec2(c.position.x - c.target.x, c.position.z - c.target.z)), radius, 1e-4f);
  }
  EXPECT_LT(glm::length(orbitCamera(start, 0, 16).position - start.position), 1e-5f);
  EXPECT_GT(glm::length(orbitCamera(start, 8, 16).position - start.position), 1.9f * radius);
}

TEST(Camera, FlythroughStartsAtTheStartPassesOverTheTargetAndEndsBeyondIt) {
  Camera start;
  start.position = {3.0f, 2.0f, 4.0f};
  start.target = {1.0f, 0.5f, -1.0f};
  const glm::vec3 offset = start.position - start.target;
  EXPECT_LT(glm::length(flythroughCamera(start, 0, 9).position - start.position), 1e-5f);
  const Camera middle = flythroughCamera(start, 4, 9), last = flythroughCamera(start, 8, 9);
  EXPECT_LT(glm::length(glm::vec2(middle.position.x - start.target.x, middle.position.z - start.target.z)), 1e-4f);
  EXPECT_GT(middle.position.y, start.target.y);
  EXPECT_LT(glm::dot(last.position - start.target, offset), 0.0f) << "the path ends on the far side";
  for (uint32_t f = 0; f < 9; ++f) {
    const Camera c = flythroughCamera(start, f, 9);
    EXPECT_GT(glm::length(c.target - c.position), 0.1f);
    EXPECT_LT(glm::dot(c.target - c.position, offset), 0.0f) << "looks ahead, away from the start, frame " << f;
  }
}

TEST(Camera, ProjectionIsVulkanClipSpace) {
  Camera c;
  c.position = {0, 0, 5};
  c.target = {0, 0, 0};
  const glm::mat4 vp = c.projection(1.0f) * c.view();
  const glm::vec4 nearPoint = vp * glm::vec4(0, 0, 5 - c.znear, 1);
  const glm::vec4 farPoint = vp * glm::vec4(0, 0, 5 - c.zfar, 1);
  EXPECT_NEAR(nearPoint.z / nearPoint.w, 0.0f, 1e-5f);
  EXPECT_NEAR(farPoint.z / farPoint.w, 1.0f, 1e-5f);
  const glm::vec4 up = vp * glm::vec4(0, 1, 0, 1);
  EXPECT_LT(up.y / up.w, 0.0f) << "world up maps to the top row (negative y) in Vulkan";
}


// The benchmark's paths start 40% closer than the default camera: their near plane must not
// cut into the scene, or a single-object scene is rendered with its front clipped away.
TEST(Camera, PathsFromTheStartCameraClipNothingOfTheScene) {
  Scene scene;
  scene.boundsMin = {-1.34f, -0.97f, -0.80f};
  scene.boundsMax = {1.34f, 0.95f, 0.83f};
  const Camera start = pathStartCamera(scene, 16.0f / 9.0f);
  auto distanceToBounds = [&](const glm::vec3& p) { return glm::length(p - glm::clamp(p, scene.boundsMin, scene.boundsMax)); };
  const float radius = 0.5f * glm::length(scene.boundsMax - scene.boundsMin);
  for (uint32_t f = 0; f < 16; ++f) {
    const Camera c = orbitCamera(start, f, 16);
    EXPECT_LT(c.znear, distanceToBounds(c.position)) << "orbit frame " << f << " clips the scene";
    EXPECT_GT(c.zfar, glm::length(c.position - c.target) + radius) << "orbit frame " << f;
  }
  EXPECT_LE(start.znear, 0.01f * radius) << "the fly-through enters the bounds";
}

// A single model (Suzanne's bounds) is flown over, clear of its box, and kept in view; a
// level whose centre is open ground keeps the plain fly-through, looking ahead.
TEST(Camera, AFlythroughClearsAModelInItsWayAndKeepsItInView) {
  // A closed box the size of Suzanne's bounds, and the same box's walls without lid or floor.
  const glm::mat4 size = glm::scale(glm::mat4(1.0f), glm::vec3(1.34f, 0.96f, 0.815f));
  Scene scene = test::sceneWithMesh(test::subdividedCube(2), size);
  const Object model = scene.objects[0];
  const Camera start = pathStartCamera(scene, 16.0f / 9.0f);
  const FlythroughShape shape = flythroughShape(scene, start);
  EXPECT_TRUE(shape.lookAtTarget);
  const float radius = 0.5f * glm::length(scene.boundsMax - scene.boundsMin);
  EXPECT_NEAR(start.target.y + shape.overHeight, scene.boundsMax.y + 0.05f * radius, 1e-4f);
  for (uint32_t f = 0; f < 9; ++f) {
    const Camera c = flythroughCamera(start, f, 9, shape);
    const glm::vec3 p = c.position;
    EXPECT_FALSE(glm::all(glm::greaterThanEqual(p, model.boundsMin)) && glm::all(glm::lessThanEqual(p, model.boundsMax))) << "inside at frame " << f;
    EXPECT_EQ(c.target, start.target) << "the model stays in view, frame " << f;
  }
  EXPECT_GT(flythroughCamera(start, 4, 9, shape).position.y, scene.boundsMax.y) << "over the top";
  // A level: the path's middle is in the open between walls (nothing above it).
  Scene level = scene;
  Mesh& walls = level.meshes[level.objects[0].mesh];
  std::vector<uint32_t> sides;
  for (size_t t = 0; t + 2 < walls.indices.size(); t += 3) {
    const float y = walls.vertices[walls.indices[t]].position.y + walls.vertices[walls.indices[t + 1]].position.y + walls.vertices[walls.indices[t + 2]].position.y;
    if (std::fabs(y) < 2.9f) sides.insert(sides.end(), walls.indices.begin() + t, walls.indices.begin() + t + 3);  // not the lid or floor
  }
  walls.indices = sides;
  const FlythroughShape open = flythroughShape(level, start);
  EXPECT_FALSE(open.lookAtTarget);
  EXPECT_EQ(open.overHeight, 0.0f);
  EXPECT_EQ(flythroughCamera(start, 3, 9, open).position, flythroughCamera(start, 3, 9).position);
}

}  // namespace
}  // namespace raybudget
