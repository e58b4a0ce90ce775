#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

layout(push_constant) uniform PushBlock { DrawPush push; };
layout(location = 0) out vec2 outUv;
layout(location = 1) out float outAlpha;  // COLOR_0's alpha, which masks as the base colour's does

void main() {
  GpuVertex v = vertices[gl_VertexIndex];
  outUv = vec2(v.positionU.w, v.normalV.w);
  outAlpha = v.color.a;
  gl_Position = push.viewProj * (objects[push.objectMaterial.x].model * vec4(v.positionU.xyz, 1.0));
}
