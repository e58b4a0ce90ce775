#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

layout(push_constant) uniform PushBlock { DrawPush push; };
layout(location = 0) out vec2 outUv;

void main() {
  GpuVertex v = vertices[gl_VertexIndex];
  outUv = vec2(v.positionU.w, v.normalV.w);
  gl_Position = push.viewProj * (objects[push.objectMaterial.x].model * vec4(v.positionU.xyz, 1.0));
}
