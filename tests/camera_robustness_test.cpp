// Cameras at the edges: looking straight up or down, sitting inside an object, at the near
// plane: the frame has no NaN or Inf; a degenerate camera given by the API is refused with a
// message naming the fault.
#include <cmath>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "raybudget/error.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

size_t nonFinite(const FrameImages& img) {
  size_t bad = 0;
  for (uint16_t h : img.hdrRgba16) bad += !std::isfinite(glm::unpackHalf1x16(h));
  return bad;
}

TEST(CameraRobustness, StraightUpDownInsideAndAtTheNearPlaneRenderFinite) {
  const Scene scene = loadScene(test::defaultScenePath());
  Renderer renderer(scene, test::settingsFor(Policy::All, 64, 40));
  const Camera start = defaultCamera(scene, renderer.aspect());
  const glm::vec3 centre = 0.5f * (scene.boundsMin + scene.boundsMax);
  Camera down = start, up = start, inside = start, near = start;
  down.position = centre + glm::vec3(0.0f, 8.0f, 0.0f);
  down.target = centre;  // along -up
  up.position = centre;
  up.target = centre + glm::vec3(0.0f, 5.0f, 0.0f);  // along +up
  const Object& crate = scene.objects.at(test::objectNamed(scene, "crate_0"));
  inside.position = 0.5f * (crate.boundsMin + crate.boundsMax);  // inside a closed box
  inside.target = inside.position + glm::vec3(1.0f, 0.0f, 0.0f);
  near.znear = 1e-4f;  // a wall a hair beyond the near plane
  near.position = glm::vec3(crate.boundsMin.x - 2e-4f, 0.5f * (crate.boundsMin.y + crate.boundsMax.y), 0.5f * (crate.boundsMin.z + crate.boundsMax.z));
  near.target = near.position + glm::vec3(1.0f, 0.0f, 0.0f);
  for (const Camera* c : {&down, &up, &inside, &near}) {
    const glm::mat4 v = c->view();
    for (int i = 0; i < 16; ++i) ASSERT_TRUE(std::isfinite(v[i / 4][i % 4]));
    renderer.render(*c);
    renderer.finish();
    EXPECT_EQ(nonFinite(renderer.readback()), 0u) << "camera " << (c - &down);
  }
  test::expectValidationClean(renderer.validationMessages());
}

TEST(CameraRobustness, ADegenerateCameraIsRefused) {
  const Scene scene = loadScene(test::defaultScenePath());
  Renderer renderer(scene, test::settingsFor(Policy::None, 32, 20));
  const Camera good = defaultCamera(scene, renderer.aspect());
  auto refused = [&](Camera c, const std::string& expected) {
    try {
      renderer.render(c);
      ADD_FAILURE() << "a camera with " << expected << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  Camera c = good;
  c.target = c.position;
  refused(c, "target is at its position");
  c = good;
  c.position.x = NAN;
  refused(c, "non-finite");
  c = good;
  c.up = glm::vec3(0.0f);
  refused(c, "up vector is zero");
  c = good;
  c.yfov = 0.0f;
  refused(c, "field of view");
  c = good;
  c.znear = 2.0f;
  c.zfar = 1.0f;
  refused(c, "0 < znear < zfar");
  EXPECT_NO_THROW(renderer.render(good));  // nothing was recorded for the refused ones
  renderer.finish();
  test::expectValidationClean(renderer.validationMessages());
}

}  // namespace
}  // namespace raybudget
