// The compute tracer on the GPU: the same hits as its CPU reference and as Embree, no ray
// slipping through a closed mesh, and no self-intersection of offset secondary rays.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstring>

#include "bvh/cpu_rayquery.h"
#include "bvh/embree_oracle.h"
#include "passes/batch_tracer.h"
#include "shared/offset_ray.h"
#include "support/procedural.h"
#include "bvh/ray_sets.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"
#include "vk/context.h"

namespace raybudget {
namespace {

using TracerGpu = test::ValidatedGpuTest;

// The default scene with its BVH and Embree, and rays from its camera: primary, then shadow
// rays to a light and incoherent bounces from their hits.
struct DefaultSceneRays {
  Scene scene = loadScene(test::defaultScenePath());
  bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  bvh::EmbreeOracle oracle{scene};
  std::vector<bvh::OracleRay> primary;
  bvh::SecondaryRays secondary;
  DefaultSceneRays(uint32_t width, uint32_t height, uint32_t seed)
      : primary(bvh::primaryRays(defaultCamera(scene, 4.0f / 3.0f), width, height)),
        secondary(bvh::secondaryRays(scene, oracle, primary, glm::vec3(-6.0f, 3.8f, -6.0f), seed)) {}
};

TEST_F(TracerGpu, MatchesTheCpuReferenceAndEmbreeOnTheDefaultScene) {
  const DefaultSceneRays d(256, 192, 3);
  passes::BatchTracer tracer(ctx, d.bvh);
  for (const auto* set : {&d.primary, &d.secondary.incoherent}) {
    const std::vector<gpu::GpuHit> hits = tracer.trace(bvh::toGpuRays(*set), 0u);
    size_t cpuMismatch = 0, embreeMismatch = 0;
    for (size_t i = 0; i < set->size(); ++i) {
      const bvh::OracleRay& r = (*set)[i];
      const bool gpuHit = hits[i].flags & 1u;
      const bvh::TraceResult c = bvh::traceCpu(d.bvh, r.origin, r.dir, r.tMin, r.tMax, 0u);
      // Same hits on the same triangles; t within a few ulps of the coordinates, since the
      // GPU compiler may fuse the object-space transform's multiply-adds.
      const float ulps = 1e-6f * (glm::length(r.origin) + c.t * glm::length(r.dir)) / glm::length(r.dir);
      if (gpuHit != c.hit || (gpuHit && (hits[i].object != c.object || hits[i].primitive != c.primitive ||
                                         std::fabs(hits[i].t - c.t) > 1e-6f * c.t + ulps)))
        ++cpuMismatch;
      const bvh::OracleHit e = d.oracle.intersect(r);
      if (gpuHit != e.hit || (gpuHit && std::fabs(hits[i].t - e.t) > 1e-4f * e.t + 1e-5f * (glm::length(r.origin) + e.t)))
        ++embreeMismatch;
    }
    EXPECT_EQ(cpuMismatch, 0u) << "GPU and CPU run the same traversal source";
    EXPECT_LE(double(embreeMismatch), 1e-4 * double(set->size())) << embreeMismatch << " of " << set->size();
  }
  // Any-hit shadow rays agree with rtcOccluded1.
  const std::vector<gpu::GpuHit> shadow = tracer.trace(bvh::toGpuRays(d.secondary.shadow), RB_RQ_TERMINATE_ON_FIRST_HIT);
  size_t shadowMismatch = 0;
  for (size_t i = 0; i < shadow.size(); ++i) shadowMismatch += bool(shadow[i].flags & 1u) != d.oracle.occluded(d.secondary.shadow[i]);
  EXPECT_LE(double(shadowMismatch), 1e-4 * double(shadow.size())) << shadowMismatch << " of " << shadow.size();
}

// Binning hands the device the same rays in another order: every ray's hit is the same
// (each ray's traversal is its own), and the hits come back in the caller's order.
TEST_F(TracerGpu, BinnedOrderChangesNoHit) {
  const DefaultSceneRays d(192, 144, 5);
  passes::BatchTracer tracer(ctx, d.bvh);
  const std::vector<gpu::GpuRay> rays = bvh::toGpuRays(d.secondary.incoherent);
  const std::vector<gpu::GpuHit> given = tracer.trace(rays, 0u);
  EXPECT_EQ(tracer.lastBinMs(), 0.0);
  const std::vector<gpu::GpuHit> binned = tracer.trace(rays, 0u, passes::BatchTracer::Order::Binned);
  EXPECT_GT(tracer.lastBinMs(), 0.0);
  ASSERT_EQ(binned.size(), given.size());
  size_t hits = 0, differ = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    hits += given[i].flags & 1u;
    differ += std::memcmp(&given[i], &binned[i], sizeof(gpu::GpuHit)) != 0;
  }
  EXPECT_GT(hits, rays.size() / 10);
  EXPECT_EQ(differ, 0u) << "of " << rays.size();
}

// The native VK_KHR_ray_query tracer and the compute tracer, same rays: same hits, the
// same object, primitive, front face and barycentrics (the geometry table maps the
// driver's geometry and primitive indices back to ours), and Embree agrees with both.
void expectNativeMatchesCompute(const vk::Context& ctx, const Scene& scene, uint32_t width, uint32_t height) {
  const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
  const bvh::EmbreeOracle oracle(scene);
  passes::BatchTracer compute(ctx, bvh);
  passes::BatchTracer native(ctx, scene);
  const auto primary = bvh::primaryRays(defaultCamera(scene, 4.0f / 3.0f), width, height);
  const glm::vec3 light = 0.5f * (scene.boundsMin + scene.boundsMax) + glm::vec3(0.2f, 0.8f, 0.3f) * glm::length(scene.boundsMax - scene.boundsMin);
  const auto secondary = bvh::secondaryRays(scene, oracle, primary, light, 3);
  size_t primaryHits = 0;
  for (int kind = 0; kind < 3; ++kind) {
    const auto& set = kind == 0 ? primary : kind == 1 ? secondary.incoherent : secondary.shadow;
    const uint32_t flags = kind == 2 ? RB_RQ_TERMINATE_ON_FIRST_HIT : 0u;
    const std::vector<gpu::GpuHit> a = compute.trace(bvh::toGpuRays(set), flags), b = native.trace(bvh::toGpuRays(set), flags);
    size_t hitMismatch = 0, attributeMismatch = 0, embreeMismatch = 0;
    for (size_t i = 0; i < set.size(); ++i) {
      const bool ha = a[i].flags & 1u, hb = b[i].flags & 1u;
      primaryHits += kind == 0 && hb;
      hitMismatch += ha != hb;
      if (kind == 2) {
        embreeMismatch += hb != oracle.occluded(set[i]);
        continue;
      }
      const bvh::OracleHit e = oracle.intersect(set[i]);
      embreeMismatch += hb != e.hit || (hb && std::fabs(b[i].t - e.t) > 1e-4f * e.t + 1e-5f * (glm::length(set[i].origin) + e.t));
      if (ha && hb &&
          (a[i].object != b[i].object || a[i].primitive != b[i].primitive || (a[i].flags & 2u) != (b[i].flags & 2u) ||
           std::fabs(a[i].t - b[i].t) > 1e-4f * a[i].t + 1e-5f * (glm::length(set[i].origin) + a[i].t) || glm::length(glm::vec2(a[i].baryWork) - glm::vec2(b[i].baryWork)) > 1e-3f))
        ++attributeMismatch;
    }
    const double allowed = 1e-4 * double(set.size()) + 1.0;  // a ray grazing an edge may go either way
    EXPECT_LE(double(hitMismatch), allowed) << scene.path.filename() << " ray set " << kind << ": " << hitMismatch << " of " << set.size();
    EXPECT_LE(double(attributeMismatch), allowed) << scene.path.filename() << " ray set " << kind << ": " << attributeMismatch;
    EXPECT_LE(double(embreeMismatch), allowed) << scene.path.filename() << " ray set " << kind << ": " << embreeMismatch;
  }
  EXPECT_GT(primaryHits, primary.size() / 100) << scene.path.filename() << ": the camera should see the scene";
}

TEST_F(TracerGpu, NativeRayQueryMatchesComputeAndEmbree) {
  if (!ctx.rayQuerySupported()) GTEST_SKIP() << ctx.properties().deviceName << " offers no VK_KHR_ray_query: native tracer not tested";
  expectNativeMatchesCompute(ctx, loadScene(test::defaultScenePath()), 256, 192);
}

TEST_F(TracerGpu, NativeRayQueryMatchesComputeOnTheCiScenes) {
  RB_REQUIRE_SHARED_SCENES();
  if (!ctx.rayQuerySupported()) GTEST_SKIP() << ctx.properties().deviceName << " offers no VK_KHR_ray_query: native tracer not tested";
  for (const auto& path : test::manifestScenes("ci")) expectNativeMatchesCompute(ctx, loadScene(path), 96, 72);
}

// `mesh` stretched 16:1:1/16 and turned, in its own object space: long diagonal triangles,
// which the BLAS build splits spatially when asked to.
Mesh stretched(Mesh mesh) {
  const glm::mat4 xf = glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1, 2, 3)) * glm::scale(glm::mat4(1.0f), glm::vec3(16.0f, 1.0f, 1.0f / 16.0f));
  for (Vertex& v : mesh.vertices) v.position = glm::vec3(xf * glm::vec4(v.position, 1.0f));
  mesh.name += " (stretched)";
  return mesh;
}

// Rays aimed exactly at vertices and at points of shared edges of closed meshes must all
// hit. Each ray comes from a random direction for which it enters the mesh through that
// point (-dir lies inside the normal cone of every face there), so a miss can only be a
// ray slipping between triangles, or past a box that a spatial split cut too tight (the
// stretched meshes, built with splits).
TEST_F(TracerGpu, NoRaySlipsThroughAClosedMesh) {
  size_t total = 0;
  const std::pair<Mesh, SpatialSplits> cases[] = {{test::icosphere(3), SpatialSplits::Auto},
                                                       {test::subdividedCube(8), SpatialSplits::Auto},
                                                       {stretched(test::icosphere(3)), SpatialSplits::Always},
                                                       {stretched(test::subdividedCube(8)), SpatialSplits::Always}};
  for (const auto& [mesh, splits] : cases) {
    const Scene scene = test::sceneWithMesh(mesh, glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1, 2, 3)));
    const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene, {splits});
    if (splits == SpatialSplits::Always) {
      EXPECT_GT(bvh.stats.references, bvh.stats.triangles * 11 / 10) << mesh.name << ": too few splits to test them";
    }
    passes::BatchTracer tracer(ctx, bvh);
    const glm::mat4& xf = scene.objects[0].transform;
    std::vector<glm::vec3> world;
    for (const Vertex& v : mesh.vertices) world.push_back(glm::vec3(xf * glm::vec4(v.position, 1.0f)));
    const size_t triCount = mesh.indices.size() / 3;
    std::vector<glm::vec3> faceNormal(triCount);
    std::vector<std::vector<uint32_t>> facesOfVertex(world.size());
    for (uint32_t t = 0; t < triCount; ++t) {
      const uint32_t* i = &mesh.indices[t * 3];
      faceNormal[t] = glm::normalize(glm::cross(world[i[1]] - world[i[0]], world[i[2]] - world[i[0]]));
      for (int k = 0; k < 3; ++k) facesOfVertex[i[k]].push_back(t);
    }
    bvh::Rng rng(11);
    std::vector<gpu::GpuRay> rays;
    const size_t perMesh = 250000;
    while (rays.size() < perMesh) {
      const uint32_t tri = uint32_t(rng.next() * float(triCount)) % uint32_t(triCount);
      const uint32_t a = mesh.indices[tri * 3], b = mesh.indices[tri * 3 + 1];
      const bool atVertex = rays.size() % 2 == 1;
      const glm::vec3 target = atVertex ? world[a] : world[a] + (world[b] - world[a]) * rng.next();
      // The faces through the target: all faces of vertex a, or the two sharing edge a-b.
      std::vector<glm::vec3> normals;
      for (uint32_t f : facesOfVertex[a]) {
        const uint32_t* i = &mesh.indices[f * 3];
        if (atVertex || i[0] == b || i[1] == b || i[2] == b) normals.push_back(faceNormal[f]);
      }
      glm::vec3 mean(0.0f);
      for (const glm::vec3& n : normals) mean += n;
      mean = glm::normalize(mean);
      glm::vec3 out;
      bool ok = false;
      for (int attempt = 0; attempt < 32 && !ok; ++attempt) {
        out = glm::normalize(mean + glm::vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f) * 1.5f);
        ok = std::all_of(normals.begin(), normals.end(), [&](const glm::vec3& n) { return glm::dot(out, n) > 0.05f; });
      }
      if (!ok) continue;
      const glm::vec3 from = target + out * 4.0f;
      rays.push_back({glm::vec4(from, 0.0f), glm::vec4(target - from, 1.5f)});  // t = 1 reaches the target
    }
    const std::vector<gpu::GpuHit> hits = tracer.trace(rays, RB_RQ_TERMINATE_ON_FIRST_HIT);
    size_t leaks = 0, cpuLeaks = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
      if ((hits[i].flags & 1u) != 0u) continue;
      ++leaks;
      cpuLeaks += !bvh::traceCpu(bvh, glm::vec3(rays[i].originTMin), glm::vec3(rays[i].dirTMax), 0.0f, 1.5f, RB_RQ_TERMINATE_ON_FIRST_HIT).hit;
    }
    EXPECT_EQ(leaks, 0u) << mesh.name << ": rays slipped through on the GPU";
    EXPECT_EQ(cpuLeaks, 0u) << mesh.name << ": rays slipped through the CPU reference";
    total += rays.size();
  }
  EXPECT_GE(total, 1000000u);
}

// Offset secondary origins: shadow rays from points on a plane and a sphere towards a light
// on their side never hit their own surface, at any scale and far from the origin.
TEST_F(TracerGpu, OffsetOriginsNeverSelfIntersect) {
  size_t rays = 0, acne = 0;
  for (float scale : {1e-3f, 1.0f, 1e4f})
    for (float distance : {0.0f, 1e3f, 1e5f})
      for (int shape = 0; shape < 2; ++shape) {
        const glm::vec3 place(distance, distance * 0.5f, -distance);
        const glm::mat4 xf = glm::translate(glm::mat4(1.0f), place) * glm::scale(glm::mat4(1.0f), glm::vec3(scale));
        const Scene scene = test::sceneWithMesh(shape == 0 ? test::quad(1.0f) : test::icosphere(3), xf);
        const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
        passes::BatchTracer tracer(ctx, bvh);
        // Primary rays from above hit the surface; their hit points become shadow-ray origins.
        bvh::Rng rng(5);
        std::vector<gpu::GpuRay> primary;
        for (int i = 0; i < 4096; ++i) {
          const glm::vec3 target = place + glm::vec3(rng.next() - 0.5f, 0.0f, rng.next() - 0.5f) * (1.2f * scale);
          const glm::vec3 from = target + glm::vec3(0.3f, 3.0f, 0.2f) * scale;
          primary.push_back({glm::vec4(from, 0.0f), glm::vec4(target + glm::vec3(0, shape ? 0.5f * scale : 0.0f, 0) - from, 1e30f)});
        }
        const std::vector<gpu::GpuHit> hits = tracer.trace(primary, 0u);
        const Mesh& mesh = scene.meshes[0];
        std::vector<gpu::GpuRay> shadow;
        for (size_t i = 0; i < hits.size(); ++i) {
          if (!(hits[i].flags & 1u)) continue;
          glm::vec3 v[3];
          for (int k = 0; k < 3; ++k) v[k] = glm::vec3(xf * glm::vec4(mesh.vertices[mesh.indices[hits[i].primitive * 3 + uint32_t(k)]].position, 1.0f));
          const float b1 = hits[i].baryWork.x, b2 = hits[i].baryWork.y;
          const glm::vec3 p = v[0] * (1.0f - b1 - b2) + v[1] * b1 + v[2] * b2;
          glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
          if (glm::dot(n, glm::vec3(primary[i].dirTMax)) > 0.0f) n = -n;
          const glm::vec3 origin = gpu::offsetRay(p, n);
          // Light low over the surface: grazing shadow rays are where acne appears first.
          const glm::vec3 toLight = glm::normalize(n + glm::vec3(3.0f, 0.0f, 1.0f) * 0.9f);
          shadow.push_back({glm::vec4(origin, 0.0f), glm::vec4(toLight * (dot(toLight, n) > 0.0f ? 1.0f : -1.0f), 1e30f)});
        }
        // A plane cannot shadow itself; a convex sphere neither (the ray leaves towards its side).
        for (const gpu::GpuHit& h : tracer.trace(shadow, RB_RQ_TERMINATE_ON_FIRST_HIT)) acne += h.flags & 1u;
        rays += shadow.size();
      }
  EXPECT_GT(rays, 60000u);
  EXPECT_EQ(acne, 0u) << acne << " of " << rays << " shadow rays hit their own surface";
}

}  // namespace
}  // namespace raybudget
