// The BVH build and the shared traversal, run on the CPU, against Embree: the same rays
// must hit the same triangles at the same distances.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>

#include "bvh/cpu_rayquery.h"
#include "bvh/embree_oracle.h"
#include "support/gltf_fixture.h"
#include "support/procedural.h"
#include "bvh/ray_sets.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

struct Agreement {
  size_t rays = 0, hitMismatch = 0, primitiveMismatch = 0, tMismatch = 0;
};

// Both triangles lie in one plane (overlapping coplanar geometry): either is a right answer.
bool coplanar(const Scene& scene, const bvh::OracleHit& a, const bvh::TraceResult& b) {
  auto plane = [&](uint32_t object, uint32_t primitive) {
    const Object& o = scene.objects[object];
    const Mesh& m = scene.meshes[o.mesh];
    glm::vec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::vec3(o.transform * glm::vec4(m.vertices[m.indices[primitive * 3 + uint32_t(k)]].position, 1.0f));
    const glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
    return glm::vec4(n, -glm::dot(n, v[0]));
  };
  const glm::vec4 pa = plane(a.object, a.primitive), pb = plane(b.object, b.primitive);
  return std::fabs(std::fabs(glm::dot(glm::vec3(pa), glm::vec3(pb))) - 1.0f) < 1e-4f &&
         std::fabs(std::fabs(pa.w) - std::fabs(pb.w)) < 1e-4f * (1.0f + std::fabs(pa.w));
}

Agreement compareClosest(const Scene& scene, const bvh::SceneBvh& bvh, const bvh::EmbreeOracle& oracle, const std::vector<bvh::OracleRay>& rays) {
  Agreement a;
  for (const bvh::OracleRay& r : rays) {
    ++a.rays;
    const bvh::OracleHit e = oracle.intersect(r);
    const bvh::TraceResult c = bvh::traceCpu(bvh, r.origin, r.dir, r.tMin, r.tMax, 0u);
    if (e.hit != c.hit) {
      ++a.hitMismatch;
      continue;
    }
    if (!e.hit) continue;
    // 1e-4 relative, plus the float resolution of the coordinates involved: Embree intersects
    // world-space triangles, we transform the ray into object space, so the two differ by a
    // few ulps of the positions (which dominates for hits very close to the origin).
    const float positionScale = glm::length(r.origin) + e.t * glm::length(r.dir);
    if (std::fabs(e.t - c.t) > 1e-4f * e.t + 1e-5f * positionScale / glm::length(r.dir)) ++a.tMismatch;
    else if ((e.object != c.object || e.primitive != c.primitive) && !coplanar(scene, e, c)) ++a.primitiveMismatch;
  }
  return a;
}

void expectAgreement(const Agreement& a, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_GT(a.rays, 0u);
  EXPECT_LE(double(a.hitMismatch), 1e-4 * double(a.rays)) << a.hitMismatch << " of " << a.rays << " rays disagree on hit/miss";
  EXPECT_LE(double(a.tMismatch), 1e-4 * double(a.rays)) << a.tMismatch << " hits differ in t by more than 1e-4 relative";
  EXPECT_LE(double(a.primitiveMismatch), 1e-4 * double(a.rays)) << a.primitiveMismatch << " hits at equal t on other, non-coplanar triangles";
}

void checkScene(const Scene& scene, const std::string& name, const bvh::BuildOptions& options) {
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene, options);
  const bvh::EmbreeOracle oracle(scene);
  const Camera cam = defaultCamera(scene, 4.0f / 3.0f);
  const auto primary = bvh::primaryRays(cam, 160, 120);
  const glm::vec3 light = 0.5f * (scene.boundsMin + scene.boundsMax) + glm::vec3(0.0f, glm::length(scene.boundsMax - scene.boundsMin), 0.0f);
  const auto secondary = bvh::secondaryRays(scene, oracle, primary, light, 7);
  expectAgreement(compareClosest(scene, bvh, oracle, primary), name + " primary");
  expectAgreement(compareClosest(scene, bvh, oracle, secondary.incoherent), name + " incoherent");
  size_t shadowMismatch = 0;
  for (const bvh::OracleRay& r : secondary.shadow)
    shadowMismatch += oracle.occluded(r) != bvh::traceCpu(bvh, r.origin, r.dir, r.tMin, r.tMax, RB_RQ_TERMINATE_ON_FIRST_HIT).hit;
  EXPECT_LE(double(shadowMismatch), 1e-4 * double(secondary.shadow.size()) + 1.0) << name << " shadow rays";
}

// Spatial splits change the tree, never a hit: every scene is checked with them forced on too.
TEST(BvhCpu, AgreesWithEmbreeOnTheDefaultScene) {
  for (const auto splits : {SpatialSplits::Auto, SpatialSplits::Always})
    checkScene(loadScene(test::defaultScenePath()), "default", {splits});
}

TEST(BvhCpu, AgreesWithEmbreeOnEveryCiScene) {
  RB_REQUIRE_SHARED_SCENES();
  for (const auto& path : test::manifestScenes("ci"))
    for (const auto splits : {SpatialSplits::Auto, SpatialSplits::Always}) checkScene(loadScene(path), path.filename().string(), {splits});
}

glm::vec3 vertexOfMesh(const Mesh& m, uint32_t t, int k) { return m.vertices[m.indices[t * 3 + uint32_t(k)]].position; }

// Leaf references of every BLAS: the leaf box (rounded outwards) and the mesh triangle.
struct LeafRef {
  glm::vec3 lo, hi;
  uint32_t triangle;
};

std::vector<LeafRef> blasLeafRefs(const bvh::SceneBvh& bvh) {
  std::vector<LeafRef> refs;
  for (const gpu::GpuBvhNode& n : bvh.nodes) {
    const std::ptrdiff_t at = &n - bvh.nodes.data();
    if (at == RB_BVH_TLAS_ROOT_NODE || at >= std::ptrdiff_t(bvh.tlasRoot)) continue;  // TLAS leaves hold instances
    for (int side = 0; side < 2; ++side) {
      const glm::vec4 lo = side ? n.rightMinIndex : n.leftMinIndex, hi = side ? n.rightMaxCount : n.leftMaxCount;
      const uint32_t index = std::bit_cast<uint32_t>(lo.w), count = std::bit_cast<uint32_t>(hi.w);
      if (count == 0 || lo.x > hi.x) continue;  // inner node, or the empty child of a one-leaf tree
      for (uint32_t t = index; t < index + count; ++t)
        refs.push_back({glm::vec3(lo), glm::vec3(hi), std::bit_cast<uint32_t>(bvh.triangles[t].v0Primitive.w)});
    }
  }
  return refs;
}

// Every object once in the TLAS; every triangle of a one-mesh scene in at least one leaf
// (exactly one without spatial splits), and every point of it inside the box of a leaf that
// holds it: sampled points, vertices included, computed in double.
void expectWellFormed(const Scene& scene, const bvh::SceneBvh& bvh) {
  const bool splits = bvh.stats.splitMeshes > 0;
  ASSERT_EQ(bvh.instances.size(), scene.objects.size());
  std::vector<int> seen(scene.objects.size(), 0);
  for (const gpu::GpuInstance& i : bvh.instances) ++seen[i.blasObjectMask.y];
  for (int s : seen) EXPECT_EQ(s, 1);
  size_t triangles = 0, shared = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (bvh.blas[i].sharedWith >= 0) {
      ++shared;
      EXPECT_EQ(bvh.blas[i].root, bvh.blas[size_t(bvh.blas[i].sharedWith)].root);
    } else {
      triangles += scene.meshes[i].indices.size() / 3;
    }
  }
  EXPECT_EQ(bvh.stats.triangles, triangles) << "triangles of the BLASes built, a shared one once";
  EXPECT_EQ(bvh.stats.sharedMeshes, shared);
  EXPECT_EQ(bvh.stats.references, bvh.triangles.size());
  if (!splits) {
    EXPECT_EQ(bvh.triangles.size(), triangles);
  }
  EXPECT_GT(bvh.stats.bytesPerTriangle, 48.0 * double(bvh.triangles.size()) / double(triangles));
  if (scene.meshes.size() != 1) return;
  const Mesh& mesh = scene.meshes[0];
  std::vector<std::vector<LeafRef>> leavesOf(triangles);
  for (const LeafRef& r : blasLeafRefs(bvh)) leavesOf[r.triangle].push_back(r);
  bvh::Rng rng(3);
  size_t uncovered = 0;
  for (uint32_t t = 0; t < triangles; ++t) {
    ASSERT_FALSE(leavesOf[t].empty()) << "triangle " << t << " is in no leaf";
    if (!splits) {
      EXPECT_EQ(leavesOf[t].size(), 1u);
    }
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(mesh.vertices[mesh.indices[t * 3 + uint32_t(k)]].position);
    for (int s = 0; s < 64; ++s) {
      double b1 = s < 3 ? double(s == 1) : rng.next(), b2 = s < 3 ? double(s == 2) : rng.next();
      if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
      const glm::dvec3 p = v[0] * (1.0 - b1 - b2) + v[1] * b1 + v[2] * b2;
      uncovered += std::none_of(leavesOf[t].begin(), leavesOf[t].end(), [&](const LeafRef& r) {
        return glm::all(glm::lessThanEqual(glm::dvec3(r.lo), p)) && glm::all(glm::lessThanEqual(p, glm::dvec3(r.hi)));
      });
    }
  }
  EXPECT_EQ(uncovered, 0u) << "points of triangles outside every leaf box that holds them";
}

TEST(BvhCpu, TreeIsWellFormed) {
  const Scene scene = loadScene(test::defaultScenePath());
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  EXPECT_EQ(bvh.stats.splitMeshes, 0u) << "the default scene's meshes are evenly tessellated";
  expectWellFormed(scene, bvh);
  const Scene sphere = test::sceneWithMesh(test::icosphere(3));
  expectWellFormed(sphere, bvh::buildSceneBvh(sphere));
}

// Meshes with the same triangles share one BLAS when they differ only in their one material;
// each instance brings its material. Not when the triangles' flags differ (an alpha-masked
// copy) or the materials are per triangle (several primitives).
TEST(BvhCpu, MeshesDifferingOnlyInMaterialShareABlas) {
  Scene scene = test::sceneWithMesh(test::icosphere(2));
  auto material = [](glm::vec3 color, AlphaMode alpha) {
    Material m;
    m.baseColorFactor = glm::vec4(color, 1.0f);
    m.alphaMode = alpha;
    return m;
  };
  const auto at = [](float x) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f)); };
  test::addObject(scene, test::icosphere(2), at(3.0f), material({1, 0, 0}, AlphaMode::Opaque));  // mesh 1: shares mesh 0's BLAS
  test::addObject(scene, test::icosphere(2), at(6.0f), material({0, 1, 0}, AlphaMode::Mask));    // mesh 2: other flags
  Mesh twoMaterials = test::icosphere(2);
  const uint32_t half = uint32_t(twoMaterials.indices.size() / 6 * 3);
  twoMaterials.primitives = {Primitive{0, half, 0}, Primitive{half, uint32_t(twoMaterials.indices.size()) - half, 0}};
  test::addObject(scene, twoMaterials, at(9.0f), material({0, 0, 1}, AlphaMode::Opaque));       // mesh 3: per-triangle materials
  scene.meshes[3].primitives[1].material = int32_t(scene.materials.size() - 1);
  scene.meshes[3].primitives[0].material = 1;
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  ASSERT_EQ(bvh.blas.size(), 4u);
  EXPECT_EQ(bvh.blas[1].sharedWith, 0);
  EXPECT_EQ(bvh.blas[1].root, bvh.blas[0].root);
  EXPECT_EQ(bvh.blas[2].sharedWith, -1) << "alpha-masked triangles differ in their flags";
  EXPECT_EQ(bvh.blas[3].sharedWith, -1) << "per-triangle materials differ";
  EXPECT_EQ(bvh.stats.sharedMeshes, 1u);
  expectWellFormed(scene, bvh);
  // Each object's hits report its own material, on both halves of the two-material sphere.
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    for (uint32_t t = 0; t < m.indices.size() / 3; t += 7) {
      glm::vec3 c(0.0f);
      for (int k = 0; k < 3; ++k) c += vertexOfMesh(m, t, k) / 3.0f;
      const glm::vec3 target = glm::vec3(o.transform * glm::vec4(c, 1.0f)), from = target + glm::normalize(c) * 0.5f;
      const bvh::TraceResult r = bvh::traceCpu(bvh, from, target - from, 0.0f, 1.5f, RB_RQ_OPAQUE);
      ASSERT_TRUE(r.hit);
      ASSERT_EQ(r.object, o.id);
      const Primitive& p = m.primitives[r.primitive * 3 >= m.primitives[0].indexCount ? 1 : 0];
      EXPECT_EQ(r.material, uint32_t(p.material)) << "object " << o.id << " triangle " << r.primitive;
    }
  }
}

TEST(BvhCpu, SpatialSplitsCoverEveryTriangleAndAgreeWithEmbree) {
  const Scene scene = test::sceneWithMesh(test::smallAndLargeTriangles(8, 8));
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  EXPECT_EQ(bvh.stats.splitMeshes, 1u) << "large triangles among small ones: Auto should split";
  EXPECT_GT(bvh.stats.references, bvh.stats.triangles + 50) << "the large triangles were split into pieces";
  expectWellFormed(scene, bvh);
  EXPECT_EQ(bvh::buildSceneBvh(scene, {SpatialSplits::Never}).stats.references, bvh.stats.triangles);
  checkScene(scene, "small and large triangles", {});
  const Scene cube = test::sceneWithMesh(test::subdividedCube(6), glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1, 2, 3)));
  expectWellFormed(cube, bvh::buildSceneBvh(cube, {SpatialSplits::Always}));
}

TEST(BvhCpu, FlagsCullAndTerminate) {
  const auto dir = test::freshTempDir("bvh-flags");
  // Two parallel triangles facing +z at z = 0 and z = -1; the ray comes from +z.
  const Scene scene = loadScene(
      test::GltfFixture::triangles({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {-1, -1, -1}, {1, -1, -1}, {0, 1, -1}}, {0, 1, 2, 3, 4, 5}).write(dir, "two"));
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  const glm::vec3 o(0, 0, 5), d(0, 0, -1);
  const bvh::TraceResult closest = bvh::traceCpu(bvh, o, d, 0.0f, 100.0f, 0u);
  ASSERT_TRUE(closest.hit);
  EXPECT_FLOAT_EQ(closest.t, 5.0f);
  EXPECT_EQ(closest.primitive, 0u);
  EXPECT_TRUE(closest.frontFace) << "counter-clockwise seen from the ray origin";
  EXPECT_FALSE(bvh::traceCpu(bvh, o, d, 0.0f, 100.0f, RB_RQ_CULL_FRONT).hit);
  EXPECT_TRUE(bvh::traceCpu(bvh, o, d, 0.0f, 100.0f, RB_RQ_CULL_BACK).hit);
  EXPECT_FALSE(bvh::traceCpu(bvh, o, -d, 0.0f, 100.0f, 0u).hit) << "nothing behind the origin";
  const bvh::TraceResult back = bvh::traceCpu(bvh, glm::vec3(0, 0, -5), -d, 0.0f, 100.0f, RB_RQ_CULL_BACK);
  EXPECT_FALSE(back.hit) << "seen from -z both triangles are back faces";
  EXPECT_FALSE(bvh::traceCpu(bvh, o, d, 0.0f, 4.99f, 0u).hit) << "tMax excludes the hit";
  const bvh::TraceResult beyond = bvh::traceCpu(bvh, o, d, 5.01f, 100.0f, 0u);
  ASSERT_TRUE(beyond.hit);
  EXPECT_FLOAT_EQ(beyond.t, 6.0f);
}

}  // namespace
}  // namespace raybudget
