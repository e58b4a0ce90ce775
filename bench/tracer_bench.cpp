// Rays per second of the compute tracer (lavapipe or a GPU) against Embree on this CPU,
// same scene, same rays, in one run: coherent primary rays (8x8 tile order), shadow rays
// to a point light, and incoherent rays (one cosine-distributed bounce per primary hit).
// Prints median Mrays/s of `repeats` runs, the ratio to Embree's 2-thread single-ray rate
// and to the device's own VK_KHR_ray_query (same rays, same device) where it has one; plus
// BVH build time, SAH cost, memory per triangle and traversal work per ray.
//
// usage: tracer_bench [--size N] [--repeats R] [SCENE...]
//   default scenes: data/default/court.gltf and, when ../shared is there, the bench scenes
//   ToyCar and MetalRoughSpheresNoTextures.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "bvh/embree_oracle.h"
#include "bvh/ray_binning.h"
#include "bvh/ray_sets.h"
#include "bvh/scene_bvh.h"
#include "passes/batch_tracer.h"
#include "raybudget/raybudget.h"
#include "vk/context.h"

using namespace raybudget;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double wallMs(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Runs body(begin, end) over [0, n) on `threads` threads.
void parallel(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& body) {
  std::vector<std::thread> pool;
  const size_t chunk = (n + threads - 1) / threads;
  for (unsigned t = 0; t < threads; ++t) {
    const size_t b = std::min(n, t * chunk), e = std::min(n, b + chunk);
    pool.emplace_back(body, b, e);
  }
  for (auto& th : pool) th.join();
}

struct Row {
  std::string kind;
  size_t rays;
  double embree1, embree2, packets2, compute, native;  // Mrays/s (native 0: none)
  double nodes, triangles;                     // per ray, compute tracer
};

}  // namespace

int main(int argc, char** argv) {
  uint32_t size = 1024, repeats = 3;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--size") && i + 1 < argc) size = uint32_t(std::stoul(argv[++i]));
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = uint32_t(std::stoul(argv[++i]));
    else scenes.push_back(argv[i]);
  }
  if (scenes.empty()) {
    scenes.push_back(RAYBUDGET_BENCH_DEFAULT_SCENE);
    const std::filesystem::path bench = std::filesystem::path(RAYBUDGET_BENCH_SHARED_SCENES) / "bench";
    for (const char* s : {"ToyCar/ToyCar.gltf", "MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb"})
      if (std::filesystem::exists(bench / s)) scenes.push_back((bench / s).string());
      else std::printf("(skipping %s: ../shared/scenes is absent)\n", s);
  }
  try {
    vk::Context ctx(vk::ContextOptions{false, ""});
    std::printf("tracer_bench: %ux%u rays per set, median of %u, device %s, %u CPU threads\n", size, size, repeats,
                ctx.properties().deviceName, std::thread::hardware_concurrency());
    for (const std::string& path : scenes) {
      const Scene scene = loadScene(path);
      const bvh::SceneBvh bvh = bvh::buildSceneBvh(scene);
      const bvh::EmbreeOracle oracle(scene);
      passes::BatchTracer tracer(ctx, bvh);
      std::unique_ptr<passes::BatchTracer> native;
      if (ctx.rayQuerySupported()) native = std::make_unique<passes::BatchTracer>(ctx, scene);
      float blasSah = 0.0f;
      for (const auto& b : bvh.blas) blasSah = std::max(blasSah, b.sahCost);
      size_t meshTriangles = 0;  // what the native tracer builds: each mesh its own
      for (const Mesh& m : scene.meshes) meshTriangles += m.indices.size() / 3;
      std::printf("\n%s: %zu triangles in %zu meshes, %zu objects; BVH over %zu of them (meshes with the same triangles share one "
                  "BLAS): build %.1f ms (BLAS) + %.2f ms (TLAS), %zu nodes, %.1f bytes/triangle, "
                  "SAH cost: TLAS %.1f, largest BLAS %.1f; spatial splits in %zu of %zu meshes, %zu leaf references (+%.1f%%), "
                  "%zu meshes sharing another's BLAS\n",
                  std::filesystem::path(path).filename().c_str(), meshTriangles, scene.meshes.size(), scene.objects.size(),
                  bvh.stats.triangles, bvh.stats.blasMs,
                  bvh.stats.tlasMs, bvh.stats.nodes, bvh.stats.bytesPerTriangle, bvh.tlasSahCost, blasSah, bvh.stats.splitMeshes,
                  bvh.blas.size(), bvh.stats.references,
                  100.0 * (double(bvh.stats.references) / double(std::max<size_t>(1, bvh.stats.triangles)) - 1.0), bvh.stats.sharedMeshes);
      if (native)
        std::printf("native VK_KHR_ray_query: build %.1f ms on the device, %.1f bytes/triangle\n", native->buildMs(),
                    double(native->accelBytes()) / double(std::max<size_t>(1, meshTriangles)));
      const Camera cam = defaultCamera(scene, 1.0f);
      const auto primary = bvh::primaryRays(cam, size, size);
      const glm::vec3 extent = scene.boundsMax - scene.boundsMin;
      const glm::vec3 light = 0.5f * (scene.boundsMin + scene.boundsMax) + glm::vec3(0.2f, 0.8f, 0.3f) * glm::length(extent);
      const auto secondary = bvh::secondaryRays(scene, oracle, primary, light, 1);
      // The fourth set: the incoherent rays binned by origin and direction (bvh/ray_binning.h).
      // Embree and the native tracer get them in binned order; the compute tracer bins them
      // itself (BatchTracer::Order::Binned) and its time includes the binning on the CPU.
      const std::vector<gpu::GpuRay> incoherentRays = bvh::toGpuRays(secondary.incoherent);
      std::vector<bvh::OracleRay> binnedIncoherent;
      for (uint32_t i : bvh::binRays(incoherentRays)) binnedIncoherent.push_back(secondary.incoherent[i]);
      std::vector<Row> rows;
      for (int kind = 0; kind < 4; ++kind) {
        const std::vector<bvh::OracleRay>& rays = kind == 0 ? primary : kind == 1 ? secondary.shadow : kind == 2 ? secondary.incoherent : binnedIncoherent;
        const bool any = kind == 1;
        const std::vector<gpu::GpuRay> gpuRays = bvh::toGpuRays(rays);
        std::vector<bvh::OracleHit> hits(rays.size());
        std::vector<char> blocked(rays.size());
        auto single = [&](size_t b, size_t e) {
          for (size_t i = b; i < e; ++i) {
            if (any) blocked[i] = oracle.occluded(rays[i]);
            else hits[i] = oracle.intersect(rays[i]);
          }
        };
        auto packets = [&](size_t b, size_t e) {
          b = b / 8 * 8;  // packets of 8 from the chunk start
          if (any) {
            std::vector<bool> tmp;
            bool out[8];
            for (size_t i = b; i < e; i += 8) oracle.occluded8(&rays[i], std::min<size_t>(8, e - i), out);
          } else {
            for (size_t i = b; i < e; i += 8) oracle.intersect8(&rays[i], std::min<size_t>(8, e - i), &hits[i]);
          }
        };
        std::vector<double> e1, e2, p2, gpu, nat;
        std::vector<gpu::GpuHit> gpuHits;
        // Lavapipe's own ray query crawls on some scenes (0.01 Mrays/s on ToyCar): probe it on
        // every 16th ray and, when the whole set would take over 5 s, time it on that sample.
        std::vector<gpu::GpuRay> nativeRays = gpuRays;
        if (native) {
          std::vector<gpu::GpuRay> sample;
          for (size_t i = 0; i < gpuRays.size(); i += 16) sample.push_back(gpuRays[i]);
          native->trace(sample, any ? RB_RQ_TERMINATE_ON_FIRST_HIT : 0u);
          if (native->lastGpuMs() * 16.0 > 5000.0) nativeRays = std::move(sample);
        }
        const double nativeCount = double(nativeRays.size());
        for (uint32_t r = 0; r < repeats; ++r) {
          e1.push_back(wallMs([&] { single(0, rays.size()); }));
          e2.push_back(wallMs([&] { parallel(rays.size(), 2, single); }));
          p2.push_back(wallMs([&] { parallel(rays.size() / 8 * 8, 2, packets); }));
          if (kind == 3) {
            gpuHits = tracer.trace(incoherentRays, 0u, passes::BatchTracer::Order::Binned);
            gpu.push_back(tracer.lastGpuMs() + tracer.lastBinMs());
          } else {
            gpuHits = tracer.trace(gpuRays, any ? RB_RQ_TERMINATE_ON_FIRST_HIT : 0u);
            gpu.push_back(tracer.lastGpuMs());
          }
          if (native) {
            native->trace(nativeRays, any ? RB_RQ_TERMINATE_ON_FIRST_HIT : 0u);
            nat.push_back(native->lastGpuMs());
          }
        }
        double nodes = 0.0, tris = 0.0;
        for (const auto& h : gpuHits) {
          nodes += h.baryWork.z;
          tris += h.baryWork.w;
        }
        const double n = double(rays.size());
        auto mrays = [&](const std::vector<double>& ms) { return n / (median(ms) * 1e3); };
        rows.push_back({kind == 0 ? "primary" : kind == 1 ? "shadow" : kind == 2 ? "incoherent" : "incoh.binned", rays.size(), mrays(e1), mrays(e2), mrays(p2),
                        mrays(gpu), nat.empty() ? 0.0 : nativeCount / (median(nat) * 1e3), nodes / n, tris / n});
      }
      std::printf("binning the incoherent rays: %.1f ms on the CPU (included in incoh.binned's compute figure)\n", tracer.lastBinMs());
      std::printf("%-12s %9s %10s %10s %12s %10s %7s %10s %9s %10s %9s\n", "rays", "count", "embree x1", "embree x2", "packets8 x2", "compute",
                  "ratio", "native", "vs native", "nodes/ray", "tris/ray");
      for (const Row& r : rows)
        std::printf("%-12s %9zu %10.2f %10.2f %12.2f %10.2f %6.2fx %10.2f %8.2fx %10.1f %9.1f\n", r.kind.c_str(), r.rays, r.embree1, r.embree2,
                    r.packets2, r.compute, r.compute / r.embree2, r.native, r.native > 0.0 ? r.compute / r.native : 0.0, r.nodes, r.triangles);
    }
    std::printf("\nMrays/s; ratio = compute / Embree single-ray on 2 threads; vs native = compute / VK_KHR_ray_query (0: device has none;\n"
                "timed on every 16th ray where the whole set would take it over 5 s). incoh.binned: the incoherent rays binned by\n"
                "origin and direction; the compute figure includes the binning on one CPU core.\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tracer_bench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
