// Bad input must give an Error naming the file and the problem: never a crash, a hang or a
// silently wrong scene.
#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"
#include "support/gltf_fixture.h"
#include "support/procedural.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::expectLoadError;
using test::GltfFixture;

class BadInput : public ::testing::Test {
 protected:
  std::filesystem::path dir = test::freshTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
};

TEST_F(BadInput, ValidFixtureLoads) {
  const Scene s = loadScene(GltfFixture::oneTriangle().write(dir, "ok"));
  EXPECT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.stats.triangles, 1u);
}

TEST_F(BadInput, MissingFile) { expectLoadError(dir / "nothing.gltf", "file not found"); }

TEST_F(BadInput, MalformedJson) {
  const auto p = dir / "broken.gltf";
  std::ofstream(p) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { \"mesh\": 0 ";
  expectLoadError(p, "not a valid glTF");
}

TEST_F(BadInput, MissingBufferFile) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["buffers"][0]["uri"] = "does-not-exist.bin";
  expectLoadError(f.write(dir, "missingbuf"), "not a valid glTF");
}

// A buffer URI naming a folder (the fuzzer's "%triangle.bin" decoded to the scene's own
// folder): its size reads as 2^63 - 1 on ext4, which tinygltf's reader tried to allocate.
TEST_F(BadInput, ABufferThatIsAFolderIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  std::filesystem::create_directories(dir / "folder.bin");
  f.json["buffers"][0]["uri"] = "folder.bin";
  expectLoadError(f.write(dir, "folderbuf"), "not a regular file");
  f.json["buffers"][0]["uri"] = "%triangle.bin";
  expectLoadError(f.write(dir, "percent"), "not a valid glTF");
}

TEST_F(BadInput, ShortBuffer) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.bin.resize(20);  // positions need 36 bytes
  f.json["buffers"][0]["byteLength"] = 20;
  expectLoadError(f.write(dir, "short"), "runs past the end");
}

TEST_F(BadInput, AccessorCountBeyondBufferView) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"][0]["count"] = 1000;
  expectLoadError(f.write(dir, "count"), "runs past the end of its bufferView");
}

TEST_F(BadInput, MissingAccessor) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
  expectLoadError(f.write(dir, "noaccessor"), "accessor 7 does not exist");
}

TEST_F(BadInput, IndexOutOfRange) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 5});
  expectLoadError(f.write(dir, "index"), "out of range for 3 vertices");
}

TEST_F(BadInput, NanPosition) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {std::nanf(""), 0, 0}, {0, 1, 0}});
  expectLoadError(f.write(dir, "nan"), "POSITION of vertex 1 is not finite");
}

// Real assets: NaN or zero normals are recomputed from the geometry with a warning (as
// three.js and Blender do); --strict refuses them.
TEST_F(BadInput, NanAndZeroNormalsAreRecomputedWithAWarning) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {0, 1, 2, 2, 1, 3});
  f.addNormals({{0, 0, 1}, {std::nanf(""), 0, 0}, {0, 0, 0}, {0, 0.6f, 0.8f}});
  const auto path = f.write(dir, "nannormals");
  const Scene s = loadScene(path);
  const Mesh& m = s.meshes[s.objects[0].mesh];
  EXPECT_EQ(m.vertices[0].normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(m.vertices[1].normal, glm::vec3(0, 0, 1));  // recomputed: the quad faces +z
  EXPECT_EQ(m.vertices[2].normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(m.vertices[3].normal, glm::vec3(0, 0.6f, 0.8f));  // a valid one is kept
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("2 NORMAL values are NaN, infinite or zero; recomputed"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find(path.string()), std::string::npos);
  try {
    loadScene(path, {.strict = true});
    FAIL() << "strict loading should refuse NaN normals";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("strict loading refuses what it would repair: " + path.string()), std::string::npos) << e.what();
  }
}

// Real assets: a texture whose image file is missing is dropped from its material.
TEST_F(BadInput, AMissingImageIsDroppedFromItsMaterialWithAWarning) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["images"] = {{{"uri", "no-such-image.png"}}};
  f.json["textures"] = {{{"source", 0}}};
  f.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  f.json["meshes"][0]["primitives"][0]["material"] = 0;
  const auto path = f.write(dir, "noimage");
  const Scene s = loadScene(path);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].baseColorTexture, -1);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_THROW(loadScene(path, {.strict = true}), Error);
  EXPECT_NO_THROW(loadScene(GltfFixture::oneTriangle().write(dir, "clean"), {.strict = true}));
}

TEST_F(BadInput, InfinitePosition) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, INFINITY, 0}});
  expectLoadError(f.write(dir, "inf"), "POSITION of vertex 2 is not finite");
}

TEST_F(BadInput, ZeroAreaTrianglesAreDroppedAndCounted) {
  // Triangle 0 is fine, triangle 1 repeats a vertex, triangle 2 is collinear.
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}}, {0, 1, 2, 0, 0, 1, 0, 1, 3});
  const Scene s = loadScene(f.write(dir, "degenerate"));
  EXPECT_EQ(s.stats.droppedDegenerateTriangles, 2u);
  EXPECT_EQ(s.stats.triangles, 1u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("dropped 2 zero-area triangles"), std::string::npos) << s.warnings[0];
}

TEST_F(BadInput, OnlyDegenerateGeometryIsAnError) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  expectLoadError(f.write(dir, "flat"), "no triangle geometry");
}

TEST_F(BadInput, AbsurdTransform) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["scale"] = {1e20, 1, 1};
  expectLoadError(f.write(dir, "absurd"), "absurd transform");
}

TEST_F(BadInput, ZeroScaleObjectIsSkippedWithWarning) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"].push_back({{"mesh", 0}, {"scale", {0, 0, 0}}});
  f.json["scenes"][0]["nodes"].push_back(1);
  const Scene s = loadScene(f.write(dir, "zeroscale"));
  EXPECT_EQ(s.objects.size(), 1u);
  EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) { return w.find("zero-scale") != std::string::npos; }));
}

TEST_F(BadInput, NodeCycle) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["children"] = {0};
  expectLoadError(f.write(dir, "cycle"), "cycle");
}

TEST_F(BadInput, MissingMaterial) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["meshes"][0]["primitives"][0]["material"] = 3;
  expectLoadError(f.write(dir, "material"), "material 3 does not exist");
}

TEST_F(BadInput, NegativeK) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["extras"] = {{"raybudget", {{"K", -1.0}}}};
  expectLoadError(f.write(dir, "negk"), "K = -1.000000 is negative");
}

TEST_F(BadInput, NonFiniteQ) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["extras"] = {{"raybudget", {{"Q", 1e300}}}};
  expectLoadError(f.write(dir, "infq"), "Q is not finite");
}

TEST_F(BadInput, AbsurdI) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["extras"] = {{"raybudget", {{"I", 5e7}}}};
  expectLoadError(f.write(dir, "bigi"), "exceeds the maximum");
}

TEST_F(BadInput, NonNumericParameter) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["extras"] = {{"raybudget", {{"K", "high"}}}};
  expectLoadError(f.write(dir, "textk"), "extras.raybudget.K must be a number");
}

// A node marked extras.raybudget.reflectionProbe: its transform maps [-1, 1]^3 to the box.
GltfFixture withProbeNode(const nlohmann::json& value, const std::vector<double>& scale) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"].push_back({{"name", "probe"}, {"translation", {1.0, 2.0, 3.0}}, {"scale", scale},
                             {"extras", {{"raybudget", {{"reflectionProbe", value}}}}}});
  f.json["scenes"][0]["nodes"].push_back(f.json["nodes"].size() - 1);
  return f;
}

TEST_F(BadInput, AnAuthoredReflectionProbeTakesItsBoxFromItsNode) {
  const Scene s = loadScene(withProbeNode(true, {2.0, 1.0, 4.0}).write(dir, "probe"));
  ASSERT_EQ(s.reflectionProbes.size(), 1u);
  const ReflectionProbe& p = s.reflectionProbes[0];
  EXPECT_EQ(p.name, "probe");
  EXPECT_EQ(p.center, glm::vec3(1, 2, 3));
  EXPECT_EQ(p.boxMin, glm::vec3(-1, 1, -1));
  EXPECT_EQ(p.boxMax, glm::vec3(3, 3, 7));
  ASSERT_EQ(reflectionProbesOf(s).size(), 1u) << "the authored probe replaces the default one";
  EXPECT_EQ(reflectionProbesOf(s)[0].center, p.center);
  EXPECT_TRUE(loadScene(withProbeNode(false, {1.0, 1.0, 1.0}).write(dir, "off")).reflectionProbes.empty());
}

TEST_F(BadInput, WithoutAuthoredProbesOneCoversTheBounds) {
  GltfFixture f = GltfFixture::oneTriangle();  // and a copy beside it: two objects, each spanning y (and the flat z)
  f.json["nodes"].push_back({{"mesh", 0}, {"translation", {0.2, 0.0, 0.0}}});
  f.json["scenes"][0]["nodes"].push_back(1);
  const Scene s = loadScene(f.write(dir, "plain"));
  const std::vector<ReflectionProbe> probes = reflectionProbesOf(s);
  ASSERT_EQ(probes.size(), 1u);
  EXPECT_EQ(probes[0].center, 0.5f * (s.boundsMin + s.boundsMax));
  EXPECT_TRUE(glm::all(glm::lessThan(probes[0].boxMin, s.boundsMin)) && glm::all(glm::greaterThan(probes[0].boxMax, s.boundsMax)))
      << "surfaces on the bounds lie inside the box";
}

// The default probe sits at the centre of the bounds where something spans the scene (a
// floor), but not inside a model's box (a cube around the centre); a box covering the
// scene's is no model; objects with nothing spanning them get none.
TEST(DefaultReflectionProbe, IsPlacedAmidSurroundingsAndNotInsideAModel) {
  const Material plain;
  Scene s;
  test::addObject(s, test::quad(4.0f), glm::mat4(1.0f), plain);
  test::addObject(s, test::subdividedCube(1), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)), plain);
  EXPECT_TRUE(reflectionProbesOf(s).empty()) << "the centre (0, 1, 0) is inside the cube";
  setObjectTransform(s, 1, glm::translate(glm::mat4(1.0f), glm::vec3(2.9f, 1.0f, 0.0f)));
  EXPECT_EQ(reflectionProbesOf(s).size(), 1u) << "the cube moved aside";
  Scene building;
  test::addObject(building, test::subdividedCube(1), glm::scale(glm::mat4(1.0f), glm::vec3(5.0f, 2.0f, 5.0f)), plain);
  test::addObject(building, test::subdividedCube(1), glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.0f, 3.0f)), plain);
  EXPECT_EQ(reflectionProbesOf(building).size(), 1u) << "one mesh spanning the scene is its surroundings";
  Scene grid;
  for (int i = 0; i < 9; ++i)
    test::addObject(grid, test::subdividedCube(1), glm::translate(glm::mat4(1.0f), glm::vec3(3.0f * float(i % 3), 0.0f, 3.0f * float(i / 3))), plain);
  EXPECT_TRUE(reflectionProbesOf(grid).empty()) << "nothing spans the grid of cubes";
}

TEST_F(BadInput, AReflectionProbeFlagThatIsNotABoolean) {
  expectLoadError(withProbeNode("yes", {1.0, 1.0, 1.0}).write(dir, "text"), "extras.raybudget.reflectionProbe must be true or false");
}

TEST_F(BadInput, AReflectionProbeWithoutVolume) {
  expectLoadError(withProbeNode(true, {1.0, 0.0, 1.0}).write(dir, "flat"), "the reflection probe's box");
}

TEST_F(BadInput, ReflectionProbesBeyondTheMaximumAreDroppedWithAWarning) {
  GltfFixture f = withProbeNode(true, {1.0, 1.0, 1.0});
  for (size_t i = 0; i < kMaxReflectionProbes; ++i) {
    f.json["nodes"].push_back(f.json["nodes"].back());
    f.json["scenes"][0]["nodes"].push_back(f.json["nodes"].size() - 1);
  }
  const Scene s = loadScene(f.write(dir, "many"));
  EXPECT_EQ(s.reflectionProbes.size(), kMaxReflectionProbes);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("reflection probes"), std::string::npos) << s.warnings[0];
}

TEST_F(BadInput, PointsAreSkippedWithWarning) {
  GltfFixture f = GltfFixture::oneTriangle();
  nlohmann::json points = f.json["meshes"][0]["primitives"][0];
  points["mode"] = 0;
  f.json["meshes"][0]["primitives"].push_back(points);
  const Scene s = loadScene(f.write(dir, "points"));
  EXPECT_EQ(s.stats.skippedPointLinePrimitives, 1u);
  EXPECT_EQ(s.stats.triangles, 1u);
}

TEST_F(BadInput, UnsupportedRequiredExtension) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  f.json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  expectLoadError(f.write(dir, "draco"), "KHR_draco_mesh_compression");
}

TEST_F(BadInput, TruncatedGlb) {
  const auto p = dir / "truncated.glb";
  std::ofstream(p, std::ios::binary) << "glTF\x02\x00\x00\x00\xff\xff\x00\x00";
  expectLoadError(p, "not a valid glTF");
}

TEST_F(BadInput, LightWithUnknownType) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["extensionsUsed"] = {"KHR_lights_punctual"};
  f.json["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "area"}, {"intensity", 1.0}}}}}}};
  f.json["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
  EXPECT_THROW(loadScene(f.write(dir, "arealight")), Error);
}

}  // namespace
}  // namespace raybudget
