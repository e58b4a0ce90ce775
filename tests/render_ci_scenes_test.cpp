// Every ci scene renders validation-clean, and the G-buffer's object IDs equal a CPU
// rasterisation of the same triangles except within a pixel of an edge.
#include <cmath>

#include <gtest/gtest.h>

#include "support/cpu_raster.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

constexpr uint32_t kWidth = 240, kHeight = 160;

class CiScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CiScene, RendersValidationCleanAndMatchesCpuCoverage) {
  RB_REQUIRE_SHARED_SCENES();
  const auto path = test::sharedScenesDir() / "ci" / GetParam();
  const Scene scene = loadScene(path);
  const test::RenderResult r = test::renderWithValidation(scene, kWidth, kHeight, 2);
  test::expectValidationClean(r.validation);

  const test::CpuIdImage cpu = test::rasterizeObjectIds(scene, r.camera, kWidth, kHeight);
  const test::IdComparison cmp = test::compareIds(cpu, r.images.objectIds);
  const size_t pixels = size_t(kWidth) * kHeight;
  ASSERT_GT(cmp.covered, pixels / 100) << "the oracle sees almost nothing: the default camera misses the scene";
  // Edge pixels may differ (fill-rule and float rounding); interiors may not, beyond a
  // handful for coplanar overlapping surfaces (decals, labels) that z-fight.
  EXPECT_LE(cmp.interiorMismatches, pixels / 1000) << cmp.mismatches << " mismatches in total";
  EXPECT_LE(cmp.mismatches, cmp.covered / 10 + 50);

  // Not blank: the tonemapped image varies and is not all background.
  double sum = 0.0, sumSq = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    const double l = 0.2126 * r.images.ldrRgba8[i * 4] + 0.7152 * r.images.ldrRgba8[i * 4 + 1] + 0.0722 * r.images.ldrRgba8[i * 4 + 2];
    sum += l;
    sumSq += l * l;
  }
  const double mean = sum / double(pixels), stddev = std::sqrt(std::max(sumSq / double(pixels) - mean * mean, 0.0));
  EXPECT_GT(stddev, 2.0) << "flat image";
  for (uint16_t h : r.images.hdrRgba16) {
    const uint16_t exponent = (h >> 10) & 0x1F;
    ASSERT_NE(exponent, 0x1F) << "NaN or Inf in the HDR image";
  }
}

std::vector<std::string> ciSceneNames() {
  std::vector<std::string> names;
  for (const auto& p : test::manifestScenes("ci")) names.push_back(std::filesystem::relative(p, test::sharedScenesDir() / "ci").string());
  if (names.empty()) names.push_back("Box/Box.gltf");  // skipped at run time without ../shared
  return names;
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = info.param.substr(0, info.param.find('/'));
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(SharedCi, CiScene, ::testing::ValuesIn(ciSceneNames()), testName);

}  // namespace
}  // namespace raybudget
