// A pinhole camera and the camera paths the CLI offers.
#pragma once
#include <string>

#include <glm/glm.hpp>

namespace raybudget {

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float yfov = 0.8f;  // radians
  float znear = 0.05f;
  float zfar = 500.0f;

  // Looking along `up` (straight up or down) takes another up axis: the view stays finite.
  glm::mat4 view() const;
  // Vulkan clip space: y down, depth in [0, 1].
  glm::mat4 projection(float aspect) const;
};

// Throws raybudget::Error naming `where` and the fault for a camera no image can come from:
// a non-finite value, the target at the position, a zero up vector, a field of view outside
// (0, pi), or near and far planes not with 0 < znear < zfar.
void validateCamera(const Camera& camera, const std::string& where);

// Camera `frame` of `frameCount` on a full circle around `start.target` at `start`'s height
// and distance: a deterministic orbit for benchmarks and tests.
Camera orbitCamera(const Camera& start, uint32_t frame, uint32_t frameCount);

// How a fly-through passes its target: at `overHeight` above it (0: defaultFlythroughHeight),
// looking ahead along the path, or with `lookAtTarget` at the target throughout.
struct FlythroughShape {
  float overHeight = 0.0f;
  bool lookAtTarget = false;
};

// The height above the start's target at which a fly-through from `start` passes it by
// default: a third of the start's own.
float defaultFlythroughHeight(const Camera& start);

// Camera `frame` of `frameCount` on a fly-through: from `start` over its target and out to
// the far side, looking ahead: the objects' pixels, distances and visibility change fast.
Camera flythroughCamera(const Camera& start, uint32_t frame, uint32_t frameCount, FlythroughShape shape = {});

}  // namespace raybudget
