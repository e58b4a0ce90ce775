// Binding numbers of the shared descriptor set; shaders/include/bindings.glsl declares the
// same numbers for GLSL.
#pragma once
#include <cstdint>

namespace raybudget::passes {

enum Binding : uint32_t {
  kFrameUniforms = 0,
  kObjects = 1,
  kMaterials = 2,
  kLights = 3,
  kVertices = 4,
  kTextures = 5,
  kGDepth = 6,
  kGNormal = 7,
  kGBaseMetal = 8,
  kGRoughTransIor = 9,
  kGEmissive = 10,
  kGObjectId = 11,
  kGMaterialId = 12,
  kShadowMaps = 13,
  kPointShadows = 14,
  kEnvMap = 15,
  kSkyMap = 16,
  kDirectImage = 17,
  kIndirectImage = 18,
  kHdrImage = 19,
  kLdrImage = 20,
  kSkyStorage = 21,
  kEnvStorage = 22,
  kEnvSource = 23,
  kBvhNodes = 24,
  kBvhTriangles = 25,
  kBvhInstances = 26,
  kIndices = 27,
  kShadowMask = 28,
  kGPosition = 29,
  kCoverage = 30,
  kObjectParams = 31,
  kObjectRecords = 32,
  kSelection = 33,
  kTileList = 34,
  kObjectCosts = 35,
  kTileObjects = 36,
  kItemCosts = 37,
  kShadowMapDepths = 38,
  kPointShadowDepths = 39,
  kTracedMask = 40,
  kBehindGlass = 41,
  kBehindGlassImage = 42,
  kBindingCount = 43,
};

}  // namespace raybudget::passes
