// The glTF 2.0 rules that make a file invalid (scene/gltf_rules.h, scene/accessor_reader.cpp):
// each broken one is refused naming the file and the rule, or repaired with a warning where
// docs/ROBUSTNESS.md says so, and --strict refuses the repairs.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"
#include "support/gltf_fixture.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::expectLoadError;
using test::GltfFixture;

class GltfRules : public ::testing::Test {
 protected:
  std::filesystem::path dir = test::freshTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());

  // Loads `f` expecting one warning containing `expected`, and strict loading to refuse it.
  Scene expectRepair(const GltfFixture& f, const std::string& name, const std::string& expected) {
    const auto path = f.write(dir, name);
    const Scene s = loadScene(path);
    EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(), [&](const std::string& w) {
      return w.find(expected) != std::string::npos && w.find(path.string()) != std::string::npos;
    })) << "no warning naming the file with '" << expected << "'";
    EXPECT_THROW(loadScene(path, {.strict = true}), Error);
    return s;
  }
};

TEST_F(GltfRules, AValidFileLoadsWithoutWarnings) {
  const Scene s = loadScene(GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}).write(dir, "ok"));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST_F(GltfRules, AnotherMajorVersionIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["asset"]["version"] = "3.0";
  expectLoadError(f.write(dir, "v3"), "UNKNOWN_ASSET_MAJOR_VERSION");
}

TEST_F(GltfRules, AFloatAccessorCannotBeNormalized) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"][0]["normalized"] = true;
  expectLoadError(f.write(dir, "normalized"), "ACCESSOR_NORMALIZED_INVALID");
}

TEST_F(GltfRules, AnAccessorOffsetMustBeAMultipleOfItsComponentSize) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"][0]["byteOffset"] = 2;
  expectLoadError(f.write(dir, "offset"), "ACCESSOR_OFFSET_ALIGNMENT");
}

TEST_F(GltfRules, TheBufferViewOffsetCountsTowardsAlignment) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.bin.insert(f.bin.begin(), 2, 0);  // the positions move to byte 2
  f.json["buffers"][0]["byteLength"] = f.bin.size();
  f.json["bufferViews"][0]["byteOffset"] = 2;
  expectLoadError(f.write(dir, "total"), "ACCESSOR_TOTAL_OFFSET_ALIGNMENT");
}

TEST_F(GltfRules, AByteStrideOutsideFourTo252IsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["bufferViews"][0]["byteStride"] = 6;  // (tinygltf's parser refuses it, naming byteStride)
  expectLoadError(f.write(dir, "stride"), "byteStride");
}

TEST_F(GltfRules, PositionMustBeVec3Float) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"][0]["type"] = "VEC2";
  f.json["accessors"][0]["min"] = {0, 0};
  f.json["accessors"][0]["max"] = {1, 1};
  expectLoadError(f.write(dir, "vec2"), "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT");
}

TEST_F(GltfRules, AnUnknownAttributeNameIsRefusedAndAnApplicationOneIgnored) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  f.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  auto& attributes = f.json["meshes"][0]["primitives"][0]["attributes"];
  attributes["_TEMPERATURE"] = attributes["NORMAL"];
  attributes.erase("NORMAL");
  EXPECT_NO_THROW(loadScene(f.write(dir, "application")));
  attributes["FOO"] = attributes["_TEMPERATURE"];
  expectLoadError(f.write(dir, "unknown"), "MESH_PRIMITIVE_INVALID_ATTRIBUTE");
}

TEST_F(GltfRules, IndexedSemanticsStartAtZeroWithoutGaps) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  f.addNormals({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}});  // three floats per vertex: a valid COLOR
  auto& attributes = f.json["meshes"][0]["primitives"][0]["attributes"];
  attributes["COLOR_1"] = attributes["NORMAL"];
  attributes.erase("NORMAL");
  expectLoadError(f.write(dir, "gap"), "MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY");
}

TEST_F(GltfRules, IndicesMustBeUnsignedScalarsWithoutByteStride) {
  GltfFixture f = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  f.json["bufferViews"][1]["byteStride"] = 4;
  expectLoadError(f.write(dir, "stride"), "MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE");
  f.json["bufferViews"][1].erase("byteStride");
  f.json["accessors"][1]["componentType"] = 5126;  // FLOAT
  expectLoadError(f.write(dir, "float"), "MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT");
}

TEST_F(GltfRules, TwoAttributesInOneBufferViewNeedAByteStride) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  f.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 1;
  expectLoadError(f.write(dir, "shared"), "MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE");
  f.json["bufferViews"][0]["byteStride"] = 12;  // declared: valid (both read the same floats)
  EXPECT_NO_THROW(loadScene(f.write(dir, "strided")));
}

TEST_F(GltfRules, APositionWithoutOrWithWrongBoundsIsRepairedWithAWarning) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["accessors"][0].erase("min");
  f.json["accessors"][0].erase("max");
  expectRepair(f, "nobounds", "MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS");
  f.json["accessors"][0]["min"] = {0, 0, 0};
  f.json["accessors"][0]["max"] = {1, 5, 0};
  const Scene s = expectRepair(f, "wrongbounds", "ACCESSOR_MAX_MISMATCH");
  EXPECT_EQ(s.boundsMax, glm::vec3(1, 1, 0)) << "the data's bounds, not the declared ones";
}

TEST_F(GltfRules, ANonUnitRotationIsNormalizedWithAWarning) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["rotation"] = {0, 0, 0, 2};  // the identity, twice as long
  const Scene s = expectRepair(f, "rotation", "NODE_ROTATION_NON_UNIT");
  EXPECT_EQ(s.objects[0].transform, glm::mat4(1.0f)) << "a scaled quaternion would scale the mesh by 4";
}

// The validator's NODE_MATRIX_TRS: tinygltf reads the matrix and never the TRS beside it, so
// the matrix is used, without a warning (docs/ROBUSTNESS.md).
TEST_F(GltfRules, AMatrixBesideTrsIsUsed) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
  f.json["nodes"][0]["translation"] = {9, 9, 9};
  const Scene s = loadScene(f.write(dir, "both"));
  EXPECT_EQ(s.objects[0].transform[3], glm::vec4(5, 0, 0, 1));
}

TEST_F(GltfRules, AProjectiveNodeMatrixIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["matrix"] = {1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  expectLoadError(f.write(dir, "projective"), "NODE_MATRIX_NON_TRS");
}

TEST_F(GltfRules, GeometryPlacedBeyondFloatRangeIsRefused) {
  // Finite vertices and two nodes each within the transform limit, whose product is not.
  GltfFixture f = GltfFixture::triangles({{1e26f, 0, 0}, {1e26f, 1, 0}, {1e26f, 0, 1}});
  f.json["nodes"][0]["scale"] = {1e7, 1, 1};
  f.json["nodes"].push_back({{"children", {0}}, {"scale", {1e7, 1, 1}}});
  f.json["scenes"][0]["nodes"] = {1};
  expectLoadError(f.write(dir, "overflow"), "beyond float range");
}

TEST_F(GltfRules, ACameraWhoseFarPlaneIsNotBeyondItsNearOneIsRepaired) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 1.0}, {"zfar", 0.5}}}}};
  f.json["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
  f.json["scenes"][0]["nodes"].push_back(1);
  const Scene s = expectRepair(f, "camera", "CAMERA_ZFAR_LEQUAL_ZNEAR");
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_GT(s.camera->zfar, s.camera->znear);
}


// Found by the validator oracle (tests/validator/mutants.py): tinygltf reads a negative index
// as "absent" and skips a transform array holding a string, which dropped meshes and moved
// objects without a word.
TEST_F(GltfRules, ANegativeOrFractionalIndexIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["mesh"] = -1;
  expectLoadError(f.write(dir, "negative"), "INVALID_INDEX");
  f.json["nodes"][0]["mesh"] = 0;
  f.json["nodes"][0]["children"] = {0.5};
  expectLoadError(f.write(dir, "fraction"), "/nodes/0/children/0");
  f.json["nodes"][0].erase("children");
  f.json["accessors"][0]["byteOffset"] = 1.5;
  expectLoadError(f.write(dir, "offset"), "/accessors/0/byteOffset");
}

TEST_F(GltfRules, ATransformArrayHoldingANonNumberIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["nodes"][0]["translation"] = {1, "x", 0};
  expectLoadError(f.write(dir, "translation"), "ARRAY_TYPE_MISMATCH");
}

// Fields nothing renders, of the wrong type: ignored with a warning naming the field, as the
// Khronos validator's TYPE_MISMATCH errors they are; an extensionsRequired entry that is not a
// name is refused (what the file requires cannot be known).
TEST_F(GltfRules, WrongTypesInFieldsNothingRendersAreIgnoredWithAWarning) {
  GltfFixture name = GltfFixture::oneTriangle();
  name.json["meshes"][0]["name"] = 7;
  expectRepair(name, "name", "/meshes/0/name is 7, not a string; ignored (TYPE_MISMATCH)");
  GltfFixture used = GltfFixture::oneTriangle();
  used.json["extensionsUsed"] = nlohmann::json::array({"KHR_materials_ior", 3});
  expectRepair(used, "used", "/extensionsUsed/1 is 3, not an extension's name");
  const GltfFixture indexed = GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  GltfFixture bounds = indexed;
  const int indices = bounds.json["meshes"][0]["primitives"][0]["indices"].get<int>();
  bounds.json["accessors"][size_t(indices)]["min"] = nlohmann::json::array({0.5});
  expectRepair(bounds, "bounds", "/min/0 is 0.5, not an integer for an integer component type");
  GltfFixture bad = indexed;
  bad.json["accessors"][size_t(indices)]["max"] = "all";
  expectRepair(bad, "bad", "/max is \"all\", not an array");
  GltfFixture required = GltfFixture::oneTriangle();
  required.json["extensionsRequired"] = nlohmann::json::array({false});
  expectLoadError(required.write(dir, "required"), "/extensionsRequired/0 is false, not an extension's name (TYPE_MISMATCH)");
}

// A node transform that is not an array, or a material factor of the wrong type: tinygltf
// drops them (the object renders untransformed, white or at the default roughness), so they
// are refused naming the field.
TEST_F(GltfRules, TransformsAndMaterialFactorsOfTheWrongTypeAreRefused) {
  GltfFixture node = GltfFixture::oneTriangle();
  node.json["nodes"][0]["translation"] = "far";
  expectLoadError(node.write(dir, "node"), "/nodes/0/translation is \"far\", not an array of numbers (TYPE_MISMATCH)");
  GltfFixture color = GltfFixture::oneTriangle();
  color.json["materials"] = nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.5, "red", 1.0}}}}}});
  color.json["meshes"][0]["primitives"][0]["material"] = 0;
  expectLoadError(color.write(dir, "color"), "/materials/0/pbrMetallicRoughness/baseColorFactor/2 is \"red\", not a number (ARRAY_TYPE_MISMATCH)");
  GltfFixture rough = color;
  rough.json["materials"][0]["pbrMetallicRoughness"] = {{"roughnessFactor", "smooth"}};
  expectLoadError(rough.write(dir, "rough"), "/materials/0/pbrMetallicRoughness/roughnessFactor is \"smooth\", not a number (TYPE_MISMATCH)");
}

TEST_F(GltfRules, ALightBeyondFloatRangeIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["extensionsUsed"] = {"KHR_lights_punctual"};
  f.json["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"color", {1.0, 1e40, 1.0}}}}}}}};
  f.json["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
  expectLoadError(f.write(dir, "light"), "beyond float range");
}

TEST_F(GltfRules, AMissingDefaultSceneIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["scene"] = 3;
  expectLoadError(f.write(dir, "scene"), "scene 3 does not exist");
}

TEST_F(GltfRules, AGlbWhoseHeaderLengthDiffersFromTheFileIsRefused) {
  GltfFixture f = GltfFixture::oneTriangle();
  f.json["buffers"][0].erase("uri");
  std::string json = f.json.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string glb = "glTF";
  auto u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(uint32_t(12 + 8 + json.size() + 8 + f.bin.size() + 4));  // four bytes more than written
  u32(uint32_t(json.size()));
  u32(0x4E4F534Au);
  glb += json;
  u32(uint32_t(f.bin.size()));
  u32(0x004E4942u);
  glb.append(reinterpret_cast<const char*>(f.bin.data()), f.bin.size());
  const auto path = dir / "length.glb";
  std::ofstream(path, std::ios::binary) << glb;
  expectLoadError(path, "GLB_LENGTH_MISMATCH");
}

}  // namespace
}  // namespace raybudget
