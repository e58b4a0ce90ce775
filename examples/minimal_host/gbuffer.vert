#version 460
// The host's own G-buffer raster (raybudget's encoding, docs/INTEGRATION.md): vertices come
// in world space (the host transformed them once; the scene is static here).
layout(push_constant) uniform Push {
  mat4 viewProj;
  vec4 baseColor;      // linear rgb, a unused
  vec4 material;       // metallic, roughness, transmission, IOR
  vec4 emissiveUnlit;  // emitted radiance rgb, unlit (0/1)
  uvec4 ids;           // object ID, material index, double-sided (0/1)
  vec4 camera;         // world position of the camera
} push;

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inColor;

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outColor;

void main() {
  outWorld = inWorld;
  outNormal = inNormal;
  outColor = inColor;
  gl_Position = push.viewProj * vec4(inWorld, 1.0);
}
