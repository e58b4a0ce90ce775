// EXR output holds the linear HDR values the GPU computed; PNG output is the tonemapped image.
#include <cstring>

#include <gtest/gtest.h>

#include "raybudget/image_io.h"
#include "support/gltf_fixture.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

float halfToFloat(uint16_t h) {
  const uint32_t sign = uint32_t(h >> 15) << 31, exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  uint32_t bits;
  if (exponent == 0) {
    const float v = std::ldexp(float(mantissa), -24);
    return sign ? -v : v;
  }
  bits = sign | ((exponent + 112) << 23) | (mantissa << 13);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

TEST(ImageIo, ExrRoundTripsTheRenderedHdr) {
  const auto dir = test::freshTempDir("exr");
  const Scene scene = loadScene(test::GltfFixture::oneTriangle().write(dir, "tri"));
  const test::RenderResult r = test::renderWithValidation(scene, 64, 48, 1);
  test::expectValidationClean(r.validation);
  writeExr(dir / "frame.exr", r.images.width, r.images.height, r.images.hdrRgba16);
  uint32_t w = 0, h = 0;
  const std::vector<float> back = readExr(dir / "frame.exr", w, h);
  ASSERT_EQ(w, 64u);
  ASSERT_EQ(h, 48u);
  for (size_t i = 0; i < back.size(); ++i) ASSERT_EQ(back[i], halfToFloat(r.images.hdrRgba16[i])) << "component " << i;
  writePng(dir / "frame.png", r.images.width, r.images.height, r.images.ldrRgba8);
  EXPECT_GT(std::filesystem::file_size(dir / "frame.png"), 100u);
}

TEST(ImageIo, WrongSizesAreErrors) {
  const auto dir = test::freshTempDir("io-errors");
  EXPECT_THROW(writePng(dir / "x.png", 4, 4, std::vector<uint8_t>(10)), Error);
  EXPECT_THROW(writeExr(dir / "x.exr", 4, 4, std::vector<uint16_t>(10)), Error);
  uint32_t w, h;
  EXPECT_THROW(readExr(dir / "missing.exr", w, h), Error);
}

}  // namespace
}  // namespace raybudget
