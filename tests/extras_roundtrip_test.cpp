// The editor's save path: K/Q/I written into node extras come back identically on load,
// and nothing else in the file changes.
#include <gtest/gtest.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"
#include "support/gltf_fixture.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

void expectSameGeometry(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    ASSERT_EQ(a.meshes[m].indices, b.meshes[m].indices);
    ASSERT_EQ(a.meshes[m].vertices.size(), b.meshes[m].vertices.size());
    for (size_t v = 0; v < a.meshes[m].vertices.size(); ++v) EXPECT_EQ(a.meshes[m].vertices[v].position, b.meshes[m].vertices[v].position);
  }
}

TEST(ExtrasRoundTrip, GltfKeepsParamsAndGeometry) {
  const auto dir = test::freshTempDir("roundtrip-gltf");
  const auto src = test::GltfFixture::oneTriangle().write(dir, "src");
  RayBudgetParams p;
  p.importanceK = 2.5f;
  p.raysQ = 3.0f;
  p.hysteresisI = 0.25f;
  saveRayBudgetParams(src, dir / "src.gltf", {{0, p}});  // in place, as the editor saves
  const Scene s = loadScene(dir / "src.gltf");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].params.importanceK, 2.5f);
  EXPECT_EQ(s.objects[0].params.raysQ, 3.0f);
  EXPECT_EQ(s.objects[0].params.hysteresisI, 0.25f);
  expectSameGeometry(s, loadScene(test::GltfFixture::oneTriangle().write(dir, "ref")));
}

TEST(ExtrasRoundTrip, PartialParamsStayPartial) {
  const auto dir = test::freshTempDir("roundtrip-partial");
  const auto src = test::GltfFixture::oneTriangle().write(dir, "src");
  RayBudgetParams p;
  p.raysQ = 0.0f;
  saveRayBudgetParams(src, dir / "out.gltf", {{0, p}});
  std::filesystem::copy_file(dir / "src.bin", dir / "out.bin", std::filesystem::copy_options::overwrite_existing);
  const Scene s = loadScene(dir / "out.gltf");
  EXPECT_FALSE(s.objects[0].params.importanceK.has_value());
  EXPECT_EQ(s.objects[0].params.raysQ, 0.0f);
  EXPECT_FALSE(s.objects[0].params.hysteresisI.has_value());
}

// A node that is also a reflection probe keeps that key when its K, Q, I are saved.
TEST(ExtrasRoundTrip, SavingParamsKeepsTheNodesOtherRayBudgetKeys) {
  const auto dir = test::freshTempDir("roundtrip-probe");
  test::GltfFixture f = test::GltfFixture::oneTriangle();
  f.json["nodes"][0]["extras"] = {{"raybudget", {{"reflectionProbe", true}, {"K", 9.0}}}};
  const auto src = f.write(dir, "src");
  RayBudgetParams p;
  p.raysQ = 2.0f;
  saveRayBudgetParams(src, dir / "src.gltf", {{0, p}});
  const Scene s = loadScene(dir / "src.gltf");
  EXPECT_FALSE(s.objects[0].params.importanceK.has_value()) << "K was cleared";
  EXPECT_EQ(s.objects[0].params.raysQ, 2.0f);
  EXPECT_EQ(s.reflectionProbes.size(), 1u);
}

TEST(ExtrasRoundTrip, GlbKeepsItsBinaryChunk) {
  RB_REQUIRE_SHARED_SCENES();
  const auto dir = test::freshTempDir("roundtrip-glb");
  const auto src = test::sharedScenesDir() / "ci/Duck/Duck.glb";
  const Scene before = loadScene(src);
  std::vector<std::pair<int, RayBudgetParams>> params;
  for (const Object& o : before.objects) {
    RayBudgetParams p;
    p.importanceK = 1.0f + float(o.id);
    p.hysteresisI = 0.5f;
    params.push_back({o.gltfNode, p});
  }
  saveRayBudgetParams(src, dir / "Duck.glb", params);
  const Scene after = loadScene(dir / "Duck.glb");
  ASSERT_EQ(after.objects.size(), before.objects.size());
  for (const Object& o : after.objects) {
    EXPECT_EQ(o.params.importanceK, 1.0f + float(o.id));
    EXPECT_EQ(o.params.hysteresisI, 0.5f);
  }
  expectSameGeometry(before, after);
  EXPECT_EQ(after.images.size(), before.images.size());
  EXPECT_EQ(after.images[0].rgba, before.images[0].rgba);
}

TEST(ExtrasRoundTrip, InvalidParamsAreRejectedBeforeWriting) {
  const auto dir = test::freshTempDir("roundtrip-invalid");
  const auto src = test::GltfFixture::oneTriangle().write(dir, "src");
  RayBudgetParams p;
  p.importanceK = -3.0f;
  EXPECT_THROW(saveRayBudgetParams(src, dir / "out.gltf", {{0, p}}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.gltf"));
  EXPECT_THROW(saveRayBudgetParams(src, dir / "out.gltf", {{9, RayBudgetParams{}}}), Error);
}

}  // namespace
}  // namespace raybudget
