// The boundary with a host's device (raybudget/core.h): what a device lacks, in words, and
// the renderer running on a device the host made, with the host's validation layers clean
// and the same images as on its own device.
#include <gtest/gtest.h>

#include "raybudget/raybudget.h"
#include "support/render_helpers.h"
#include "support/test_host.h"
#include "support/test_scenes.h"
#include "passes/descriptors.h"
#include "vk/device_requirements.h"

namespace raybudget {
namespace {

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const std::string& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

TEST(HostDevice, ThisMachinesDeviceLacksNothing) {
  test::TestHost host;
  EXPECT_TRUE(core::missingRequirements(host.physicalDevice()).empty());
  EXPECT_FALSE(core::missingRequirements(VK_NULL_HANDLE).empty());
}

TEST(HostDevice, MissingRequirementsNameWhatTheDeviceLacks) {
  test::TestHost host;
  const vk::DeviceCapabilities real = vk::queryCapabilities(host.physicalDevice());
  const vk::DescriptorNeeds needs = passes::descriptorNeeds(1, false);
  ASSERT_TRUE(vk::missingRequirements(real, needs).empty());

  vk::DeviceCapabilities lacking = real;
  lacking.synchronization2 = false;
  lacking.features.imageCubeArray = VK_FALSE;
  lacking.limits.maxPerStageDescriptorStorageImages = 4;
  lacking.queueFamily.reset();
  lacking.extensions.erase(std::find(lacking.extensions.begin(), lacking.extensions.end(), VK_KHR_SHADER_CLOCK_EXTENSION_NAME));
  const std::vector<std::string> missing = vk::missingRequirements(lacking, needs);
  EXPECT_EQ(missing.size(), 5u);
  for (const char* what : {"synchronization2", "imageCubeArray", "maxPerStageDescriptorStorageImages is 4", "queue family",
                           VK_KHR_SHADER_CLOCK_EXTENSION_NAME})
    EXPECT_TRUE(mentions(missing, what)) << what;
  EXPECT_TRUE(mentions(missing, real.name)) << "each line names the device";

  vk::DeviceCapabilities old = real;
  old.apiVersion = VK_API_VERSION_1_2;
  const std::vector<std::string> oldMissing = vk::missingRequirements(old, needs);
  ASSERT_EQ(oldMissing.size(), 1u);
  EXPECT_TRUE(mentions(oldMissing, "Vulkan 1.3 is required, the device offers 1.2"));

  vk::DeviceCapabilities noRayQuery = real;
  noRayQuery.rayQuery = false;
  EXPECT_TRUE(vk::missingRequirements(noRayQuery, needs).empty()) << "ray queries are optional";
  EXPECT_FALSE(vk::deviceSetup(noRayQuery).rayQueryEnabled);
}

TEST(HostDevice, AHostChainsItsOwnFeaturesAfterTheSetup) {
  test::TestHost host;
  core::DeviceSetup setup = core::deviceSetup(host.physicalDevice());
  VkPhysicalDeviceRobustness2FeaturesEXT own{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
  const core::DeviceSetup copy = setup;  // chain() relinks, so a copy is as good
  core::DeviceSetup relinked = copy;
  auto* head = static_cast<VkBaseOutStructure*>(relinked.chain(&own));
  size_t length = 0;
  bool ownAtEnd = false;
  for (VkBaseOutStructure* s = head; s; s = s->pNext, ++length) ownAtEnd = (s == reinterpret_cast<VkBaseOutStructure*>(&own));
  EXPECT_TRUE(ownAtEnd);
  EXPECT_EQ(length, relinked.rayQueryEnabled ? 7u : 5u);
  EXPECT_EQ(head, reinterpret_cast<VkBaseOutStructure*>(&relinked.features));
}

// The court under full RT on the host's device and on the renderer's own: the same pixels.
void expectSameImagesOnTheHostsDevice(Tracer tracer) {
  const Scene scene = loadScene(test::defaultScenePath());
  RenderSettings settings = test::settingsFor(Policy::All, 160, 90);
  settings.rayTracing.tracer = tracer;
  FrameImages own, hosted;
  {
    Renderer renderer(scene, settings);
    renderer.render(defaultCamera(scene, renderer.aspect()));
    own = renderer.readback();
    test::expectValidationClean(renderer.validationMessages());
  }
  test::TestHost host;
  {
    RenderSettings onHost = settings;
    onHost.validation = false;  // the host's instance has validation on
    Renderer renderer(scene, onHost, host.device());
    EXPECT_TRUE(renderer.validationMessages().empty());
    renderer.render(defaultCamera(scene, renderer.aspect()));
    hosted = renderer.readback();
  }
  test::expectValidationClean(host.validationMessages());
  ASSERT_EQ(own.ldrRgba8.size(), hosted.ldrRgba8.size());
  EXPECT_TRUE(own.ldrRgba8 == hosted.ldrRgba8);
  EXPECT_TRUE(own.hdrRgba16 == hosted.hdrRgba16);
  EXPECT_TRUE(own.objectIds == hosted.objectIds);
}

TEST(HostDevice, TheRendererOnTheHostsDeviceRendersTheSameImage) { expectSameImagesOnTheHostsDevice(Tracer::Compute); }

TEST(HostDevice, TheNativeTracerLoadsItsEntryPointsThroughTheHost) {
  if (!test::nativeTracerAvailable()) GTEST_SKIP() << "the device offers no VK_KHR_ray_query";
  expectSameImagesOnTheHostsDevice(Tracer::Native);
}

TEST(HostDevice, IncompleteHandlesAndOwnDeviceSettingsAreRefused) {
  const Scene scene = loadScene(test::defaultScenePath());
  test::TestHost host;
  RenderSettings settings = test::settingsFor(Policy::None, 64, 64);
  settings.validation = false;
  core::HostDevice incomplete = host.device();
  incomplete.queue = VK_NULL_HANDLE;
  test::expectRefusedNamingWith(scene, settings, incomplete, "queue");
  RenderSettings named = settings;
  named.device = "llvmpipe";
  test::expectRefusedNamingWith(scene, named, host.device(), "::device");
  core::HostDevice badFamily = host.device();
  badFamily.queueFamily = 99;
  test::expectRefusedNamingWith(scene, settings, badFamily, "queue family 99");
  test::expectValidationClean(host.validationMessages());
}

}  // namespace
}  // namespace raybudget
