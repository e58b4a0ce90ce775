// CPU oracle for the G-buffer's object-ID image: rasterises the scene's triangles with the
// same camera, near-plane clipping, pixel-centre sampling and a depth test.
#pragma once
#include <cstdint>
#include <vector>

#include "raybudget/camera.h"
#include "raybudget/scene.h"

namespace raybudget::test {

struct CpuIdImage {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> ids;         // 0xFFFFFFFF where no object
  std::vector<uint8_t> alphaTested;  // 1 where the front surface is alpha-masked (GPU may discard)
};

CpuIdImage rasterizeObjectIds(const Scene& scene, const Camera& camera, uint32_t width, uint32_t height);

struct IdComparison {
  size_t pixels = 0;
  size_t covered = 0;           // pixels the CPU image covers
  size_t mismatches = 0;        // all differing pixels
  size_t interiorMismatches = 0;  // differing pixels whose 3x3 CPU neighbourhood is one ID
  size_t ignored = 0;           // alpha-tested pixels, not compared
};

IdComparison compareIds(const CpuIdImage& cpu, const std::vector<uint32_t>& gpu);

}  // namespace raybudget::test
