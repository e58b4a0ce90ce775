// An equirectangular HDR image replaces the procedural sky: the background shows its texels
// (scaled by the sky intensity) in the directions the lat-long mapping gives them.
#include <cstring>
#include <fstream>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "raybudget/image_io.h"
#include "support/gltf_fixture.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

glm::vec3 hdrAt(const FrameImages& img, uint32_t x, uint32_t y) {
  const size_t i = (size_t(y) * img.width + x) * 4;
  return {glm::unpackHalf1x16(img.hdrRgba16[i]), glm::unpackHalf1x16(img.hdrRgba16[i + 1]), glm::unpackHalf1x16(img.hdrRgba16[i + 2])};
}

TEST(Environment, HdrImageLightsTheBackgroundByDirection) {
  const auto dir = test::freshTempDir("envmap");
  // Upper hemisphere red (2, 0, 0), lower hemisphere blue (0, 0, 1).
  const uint32_t w = 64, h = 32;
  std::vector<uint16_t> texels(size_t(w) * h * 4);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const glm::vec4 c = y < h / 2 ? glm::vec4(2, 0, 0, 1) : glm::vec4(0, 0, 1, 1);
      for (int k = 0; k < 4; ++k) texels[(size_t(y) * w + x) * 4 + size_t(k)] = uint16_t(glm::packHalf1x16(c[k]));
    }
  writeExr(dir / "env.exr", w, h, texels);

  Scene scene = loadScene(test::GltfFixture::oneTriangle().write(dir, "tri"));
  RenderSettings s;
  s.width = 96;
  s.height = 64;
  s.validation = true;
  s.skyIntensity = 0.5f;
  s.environmentMap = (dir / "env.exr").string();
  Renderer renderer(scene, s);
  Camera cam;
  cam.position = {0.3f, 0.3f, 4.0f};
  cam.target = {0.3f, 0.3f, 0.0f};  // horizontal: the horizon is the middle row
  renderer.render(cam);
  renderer.finish();
  const FrameImages img = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  ASSERT_EQ(img.objectIds[2 * img.width + 2], 0xFFFFFFFFu) << "corner should be background";
  const glm::vec3 top = hdrAt(img, 2, 2), bottom = hdrAt(img, 2, img.height - 3);
  EXPECT_NEAR(top.r, 1.0f, 0.02f);
  EXPECT_NEAR(top.b, 0.0f, 0.02f);
  EXPECT_NEAR(bottom.b, 0.5f, 0.01f);
  EXPECT_NEAR(bottom.r, 0.0f, 0.02f);
}

TEST(Environment, BadImageIsAnErrorNamingTheFile) {
  const auto dir = test::freshTempDir("envmap-bad");
  std::ofstream(dir / "broken.exr") << "not an exr";
  RenderSettings s;
  s.width = 32;
  s.height = 32;
  s.environmentMap = (dir / "broken.exr").string();
  try {
    Renderer renderer(loadScene(test::GltfFixture::oneTriangle().write(dir, "tri")), s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.exr"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace raybudget
