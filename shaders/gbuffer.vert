#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

layout(push_constant) uniform PushBlock { DrawPush push; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outColor;

void main() {
  GpuObject o = objects[push.objectMaterial.x];
  GpuVertex v = vertices[gl_VertexIndex];
  vec4 world = o.model * vec4(v.positionU.xyz, 1.0);
  outWorld = world.xyz;
  outNormal = mat3(o.normalMatrix) * v.normalV.xyz;
  outUv = vec2(v.positionU.w, v.normalV.w);
  outColor = v.color;
  gl_Position = frame.viewProj * world;
}
