// Each pass's descriptor layout comes from the bindings its shaders use (vk/spirv_bindings.h):
// glslang declares all of bindings.glsl in every shader, so the reflection must find the
// used ones, and never miss one (the render tests run with validation, which would report
// a binding a pipeline uses but its layout lacks).
#include <gtest/gtest.h>

#include <algorithm>

#include "compose_comp.h"
#include "passes/bindings.h"
#include "rt_effects_comp.h"
#include "rt_effects_comp_native.h"
#include "raybudget/error.h"
#include "vk/spirv_bindings.h"

namespace raybudget {
namespace {

bool has(const std::vector<uint32_t>& bindings, uint32_t b) { return std::binary_search(bindings.begin(), bindings.end(), b); }

TEST(SpirvBindings, ComposeUsesItsImagesAndNothingOfTheTracer) {
  const std::vector<uint32_t> b = vk::usedBindings(kSpirv_compose_comp);
  for (uint32_t want : {passes::kFrameUniforms, passes::kDirectImage, passes::kReflectionImage, passes::kRefractionImage, passes::kHdrImage, passes::kLdrImage})
    EXPECT_TRUE(has(b, want)) << "binding " << want;
  for (uint32_t unused : {passes::kBvhNodes, passes::kTextures, passes::kCoverage, passes::kShadowMaps, passes::kGPosition})
    EXPECT_FALSE(has(b, unused)) << "binding " << unused;
  EXPECT_LT(b.size(), size_t(passes::kBindingCount) / 4);
}

TEST(SpirvBindings, TheEffectsPassUsesTheTracerTheGBufferAndItsItemCounters) {
  for (vk::Spirv code : {vk::Spirv(kSpirv_rt_effects_comp), vk::Spirv(kSpirv_rt_effects_comp_native)}) {
    const std::vector<uint32_t> b = vk::usedBindings(code);
    for (uint32_t want : {passes::kBvhNodes, passes::kGPosition, passes::kGNormal, passes::kReflectionImage, passes::kRefractionImage, passes::kItemCosts,
                          passes::kTileList, passes::kEnvMap})
      EXPECT_TRUE(has(b, want)) << "binding " << want;
    EXPECT_FALSE(has(b, passes::kLdrImage));
    EXPECT_TRUE(std::is_sorted(b.begin(), b.end()));
  }
}

TEST(SpirvBindings, MalformedCodeIsAnError) {
  const uint32_t notSpirv[] = {1, 2, 3, 4, 5, 6};
  EXPECT_THROW(vk::usedBindings(notSpirv), Error);
  std::vector<uint32_t> truncated(kSpirv_compose_comp, kSpirv_compose_comp + 5);
  truncated.push_back((100u << 16) | 71u);  // an instruction claiming 100 words
  EXPECT_THROW(vk::usedBindings(truncated), Error);
}

}  // namespace
}  // namespace raybudget
