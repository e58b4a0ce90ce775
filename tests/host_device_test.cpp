// The boundary with a host's device (raybudget/core.h): what a device lacks, in words, and
// the renderer running on a device the host made, with the host's validation layers clean
// and the same images as on its own device.
#include <cstring>

#include <glm/gtc/packing.hpp>
#include <glm/gtx/component_wise.hpp>
#include <gtest/gtest.h>

#include "raybudget/raybudget.h"
#include "support/render_helpers.h"
#include "support/test_host.h"
#include "support/builder_scene.h"
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

#include "vk/resources.h"

namespace raybudget {
namespace {

template <typename T>
std::vector<uint8_t> bytesOf(const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(v.data());
  return {p, p + v.size() * sizeof(T)};
}

// The host's G-buffer: images of its own in core::GBuffer's encoding, filled with `frame`'s.
struct HostGBuffer {
  std::vector<vk::Image> images;
  core::GBuffer views;

  HostGBuffer(const vk::Context& ctx, const FrameImages& frame) {
    const std::pair<VkFormat, std::vector<uint8_t>> planes[] = {
        {VK_FORMAT_D32_SFLOAT, bytesOf(frame.depth)},
        {VK_FORMAT_R16G16B16A16_SFLOAT, bytesOf(frame.normals)},
        {VK_FORMAT_R8G8B8A8_UNORM, frame.baseMetal},
        {VK_FORMAT_R16G16B16A16_SFLOAT, bytesOf(frame.roughTransIor)},
        {VK_FORMAT_R16G16B16A16_SFLOAT, bytesOf(frame.emissive)},
        {VK_FORMAT_R32_UINT, bytesOf(frame.objectIds)},
        {VK_FORMAT_R32_UINT, bytesOf(frame.materialIds)},
        {VK_FORMAT_R32G32B32A32_SFLOAT, bytesOf(frame.positions)}};
    for (const auto& [format, bytes] : planes) {
      vk::ImageDesc d;
      d.format = format;
      d.width = frame.width;
      d.height = frame.height;
      d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
      images.push_back(vk::createImage(ctx, d));
      vk::uploadTexture(ctx, images.back(), bytes);
    }
    views = {images[0].view, images[1].view, images[2].view, images[3].view, images[4].view, images[5].view, images[6].view, images[7].view,
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  }
};

// One of the images the core left in outputs(), `bytesPerPixel` wide, copied out by the host.
std::vector<uint8_t> readOutput(const vk::Context& host, const core::FrameOutputs& out, VkImage image, uint32_t bytesPerPixel, uint32_t width,
                                uint32_t height) {
  const VkDeviceSize size = VkDeviceSize(width) * height * bytesPerPixel;
  const vk::Buffer buffer = vk::createBuffer(host, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  auto layout = [&](VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to) {
    vk::imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, from, to);
  };
  host.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width, height, 1};
    layout(cmd, out.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &copy);
    layout(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.layout);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  const auto* p = static_cast<const uint8_t*>(buffer.mapped);
  return {p, p + size};
}

// The composed image the core left in outputs().
std::vector<uint8_t> readLdr(const vk::Context& host, const core::FrameOutputs& out, uint32_t width, uint32_t height) {
  return readOutput(host, out, out.ldr, 4, width, height);
}

// An R16G16B16A16_SFLOAT output's RGB per pixel.
std::vector<glm::vec3> readHalfRgb(const vk::Context& host, const core::FrameOutputs& out, VkImage image, uint32_t width, uint32_t height) {
  const std::vector<uint8_t> bytes = readOutput(host, out, image, 8, width, height);
  std::vector<glm::vec3> rgb(size_t(width) * height);
  for (size_t p = 0; p < rgb.size(); ++p) {
    uint16_t h[4];
    std::memcpy(h, bytes.data() + 8 * p, sizeof(h));
    rgb[p] = glm::vec3(glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]));
  }
  return rgb;
}

// The standalone renderer's frame of `scene` from its default camera (returned in `cam`),
// with the G-buffer read back.
FrameImages standaloneFrame(const Scene& scene, const RenderSettings& settings, Camera& cam) {
  Renderer renderer(scene, settings);
  cam = defaultCamera(scene, renderer.aspect());
  renderer.render(cam);
  FrameImages img = renderer.readback(true);
  test::expectValidationClean(renderer.validationMessages());
  return img;
}

// A standalone renderer's G-buffer, handed to the core on the host's device as the host's
// own: the frame recorded into the host's command buffer shows the same pixels, skips the
// raster, and reports its timings once its slot comes round again.
TEST(HostDevice, AFrameRecordedIntoTheHostsCommandBufferFromItsGBufferMatches) {
  const Scene scene = loadScene(test::defaultScenePath());
  const RenderSettings settings = test::settingsFor(Policy::All, 160, 90);
  Camera cam;
  const FrameImages own = standaloneFrame(scene, settings, cam);
  ASSERT_EQ(own.depth.size(), size_t(160 * 90));
  test::TestHost host;
  {
    const vk::Context hostCtx(host.device());  // the test's own helpers, on the host's device
    const HostGBuffer gbuffer(hostCtx, own);
    RenderSettings onHost = settings;
    onHost.validation = false;
    core::Context core(host.device(), scene, onHost);
    hostCtx.submitAndWait([&](VkCommandBuffer cmd) { core.recordFrame(cmd, cam, &gbuffer.views); });
    EXPECT_TRUE(core.completedFrames().empty()) << "no slot came round yet";
    const core::FrameOutputs out = core.outputs();
    EXPECT_TRUE(out.hdr && out.ldr && out.hdrView && out.ldrView && out.direct && out.reflection && out.refraction && out.shadowVisibility);
    EXPECT_TRUE(readLdr(hostCtx, out, 160, 90) == own.ldrRgba8) << "the host's G-buffer gives the standalone frame";
    for (int i = 0; i < 2; ++i) hostCtx.submitAndWait([&](VkCommandBuffer cmd) { core.recordFrame(cmd, cam, &gbuffer.views); });
    const std::vector<FrameTiming> done = core.completedFrames();
    ASSERT_EQ(done.size(), 1u);
    EXPECT_EQ(done[0].frame, 0u);
    EXPECT_FALSE(done[0].passMs[size_t(Pass::GBuffer)].has_value());
    EXPECT_EQ(done[0].skipped[size_t(Pass::GBuffer)], PassSkip::HostGBuffer);
    EXPECT_TRUE(done[0].passMs[size_t(Pass::TraceShadows)].has_value());
    EXPECT_TRUE(core.completedFrames().empty()) << "each frame's timings are returned once";
    const std::vector<FrameTiming> rest = core.completedFrames(true);
    ASSERT_EQ(rest.size(), 2u) << "the host says every recorded frame completed";
    EXPECT_EQ(rest[0].frame, 1u);
    EXPECT_EQ(rest[1].frame, 2u);
    core::GBuffer missing = gbuffer.views;
    missing.position = VK_NULL_HANDLE;
    EXPECT_THROW(hostCtx.submitAndWait([&](VkCommandBuffer cmd) { core.recordFrame(cmd, cam, &missing); }), Error);
  }
  test::expectValidationClean(host.validationMessages());
}

// The outputs hold the frame's terms apart, as a host composing its own reflections or
// refractions needs them: the HDR image is their sum, refracted light stands only on
// transmissive surfaces, and the mirror and the glass carry the terms they show.
TEST(HostDevice, TheOutputsHoldTheDirectReflectedAndRefractedLightApart) {
  const Scene scene = loadScene(test::defaultScenePath());
  const RenderSettings settings = test::settingsFor(Policy::All, 160, 90);
  Camera cam;
  const FrameImages own = standaloneFrame(scene, settings, cam);
  const uint32_t mirror = test::objectNamed(scene, "mirror_panel"), glass = test::objectNamed(scene, "glass_sphere");
  ASSERT_NE(mirror, test::kNoObjectNamed);
  ASSERT_NE(glass, test::kNoObjectNamed);
  test::TestHost host;
  {
    const vk::Context hostCtx(host.device());
    const HostGBuffer gbuffer(hostCtx, own);
    RenderSettings onHost = settings;
    onHost.validation = false;
    core::Context core(host.device(), scene, onHost);
    hostCtx.submitAndWait([&](VkCommandBuffer cmd) { core.recordFrame(cmd, cam, &gbuffer.views); });
    const core::FrameOutputs out = core.outputs();
    const auto direct = readHalfRgb(hostCtx, out, out.direct, 160, 90), reflection = readHalfRgb(hostCtx, out, out.reflection, 160, 90),
               refraction = readHalfRgb(hostCtx, out, out.refraction, 160, 90), hdr = readHalfRgb(hostCtx, out, out.hdr, 160, 90);
    size_t mirrorPixels = 0, glassPixels = 0, opaqueRefracting = 0, sumsOff = 0;
    glm::vec3 mirrorReflection(0.0f), glassRefraction(0.0f);
    for (size_t p = 0; p < hdr.size(); ++p) {
      const glm::vec3 sum = glm::max(direct[p] + reflection[p] + refraction[p], glm::vec3(0.0f));
      if (glm::any(glm::greaterThan(glm::abs(sum - hdr[p]), 2e-3f * glm::max(sum, glm::vec3(1.0f))))) ++sumsOff;
      const uint32_t id = own.objectIds[p];
      if (id == 0xFFFFFFFFu) continue;
      if (scene.materials[own.materialIds[p]].transmission == 0.0f && refraction[p] != glm::vec3(0.0f)) ++opaqueRefracting;
      if (id == mirror) ++mirrorPixels, mirrorReflection += reflection[p];
      if (id == glass) ++glassPixels, glassRefraction += refraction[p];
    }
    EXPECT_EQ(sumsOff, 0u) << "hdr = direct + reflection + refraction";
    EXPECT_EQ(opaqueRefracting, 0u) << "refracted light only on transmissive surfaces";
    ASSERT_GT(mirrorPixels, 20u);
    ASSERT_GT(glassPixels, 20u);
    // The mirror's image is its reflection; the clear glass shows mostly what is behind it.
    EXPECT_GT(glm::compMin(mirrorReflection) / float(mirrorPixels), 0.05f);
    EXPECT_GT(glm::compMin(glassRefraction) / float(glassPixels), 0.05f);
  }
  test::expectValidationClean(host.validationMessages());
}

// A host's G-buffer without the optional layers target: each pixel's clearcoat, sheen and
// specular come from its material's factors, which shades a scene of factor-only layered
// materials as the standalone renderer (which writes the layers) does, within the layers
// target's 8-bit quantisation.
TEST(HostDevice, AHostGBufferWithoutLayersShadesLayeredMaterialsFromTheirFactors) {
  Scene scene = loadScene(test::defaultScenePath());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    Material& m = scene.materials[i];
    if (i % 3 == 0) m.clearcoat = 1.0f, m.clearcoatRoughness = 0.2f;
    if (i % 3 == 1) m.sheenColor = glm::vec3(0.9f, 0.5f, 0.2f), m.sheenRoughness = 0.5f;
    if (i % 3 == 2) m.specular = 0.5f, m.specularColor = glm::vec3(2.0f, 1.0f, 0.5f);
  }
  // Full RT: the glass traced (a host's G-buffer has no behind-glass frame to show).
  const RenderSettings settings = test::settingsFor(Policy::All, 160, 90);
  Camera cam;
  const FrameImages own = standaloneFrame(scene, settings, cam);
  const FrameImages plain = standaloneFrame(loadScene(test::defaultScenePath()), settings, cam);
  test::TestHost host;
  {
    const vk::Context hostCtx(host.device());
    const HostGBuffer gbuffer(hostCtx, own);
    ASSERT_EQ(gbuffer.views.layers, VkImageView(VK_NULL_HANDLE));
    RenderSettings onHost = settings;
    onHost.validation = false;
    core::Context core(host.device(), scene, onHost);
    hostCtx.submitAndWait([&](VkCommandBuffer cmd) { core.recordFrame(cmd, cam, &gbuffer.views); });
    const std::vector<uint8_t> hosted = readLdr(hostCtx, core.outputs(), 160, 90);
    int worst = 0, layered = 0;
    for (size_t c = 0; c < hosted.size(); ++c) {
      if (c % 4 == 3) continue;
      worst = std::max(worst, std::abs(int(hosted[c]) - int(own.ldrRgba8[c])));
      layered = std::max(layered, std::abs(int(plain.ldrRgba8[c]) - int(own.ldrRgba8[c])));
    }
    EXPECT_LE(worst, 3) << "the factors give the layers the standalone G-buffer held";
    EXPECT_GT(layered, 20) << "the layers change the frame";
  }
  test::expectValidationClean(host.validationMessages());
}

}  // namespace
}  // namespace raybudget

namespace raybudget {
namespace {

// A host's arrays (SceneBuilder) render like the glTF they came from: the same frame under
// full RT, byte for byte.
TEST(HostDevice, ASceneFromTheHostsArraysRendersLikeTheGltf) {
  const Scene loaded = loadScene(test::defaultScenePath());
  const Scene built = test::rebuiltThroughBuilder(loaded);
  std::vector<uint8_t> frames[2];
  int k = 0;
  for (const Scene* scene : {&loaded, &built}) {
    Renderer renderer(*scene, test::settingsFor(Policy::All, 160, 96));
    renderer.render(defaultCamera(*scene, renderer.aspect()));
    renderer.finish();
    frames[k++] = renderer.readback().ldrRgba8;
    test::expectValidationClean(renderer.validationMessages());
  }
  ASSERT_EQ(frames[0].size(), frames[1].size());
  size_t differing = 0;
  for (size_t i = 0; i < frames[0].size(); ++i) differing += frames[0][i] != frames[1][i];
  EXPECT_EQ(differing, 0u) << "channels differ";
}

}  // namespace
}  // namespace raybudget
