#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

// Only alpha-masked materials use this stage: opaque casters render depth-only.
layout(push_constant) uniform PushBlock { DrawPush push; };
layout(location = 0) in vec2 inUv;

void main() {
  GpuMaterial m = materials[push.objectMaterial.y];
  float alpha = m.baseColorFactor.a;
  if (m.textures.x >= 0) alpha *= texture(textures[nonuniformEXT(m.textures.x)], inUv).a;
  if (alpha < m.emissiveAlphaCutoff.w) discard;
}
