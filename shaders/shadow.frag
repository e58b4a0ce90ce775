#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

// Only alpha-masked materials use this stage: opaque casters render depth-only. The alpha is
// the G-buffer's and the tracer's: base colour factor x vertex colour x texture.
layout(push_constant) uniform PushBlock { DrawPush push; };
layout(location = 0) in vec2 inUv;
layout(location = 1) in float inAlpha;

// The mask is sampled at its finest level, material_layers.glsl's default, as the tracer's alpha
// test samples it: at the coarser level the light's view would pick, thin masked features
// average below the cut-off and the map misses blockers the rays hit.
#include "include/material_layers.glsl"

void main() {
  GpuMaterial m = materials[push.objectMaterial.y];
  float alpha = m.baseColorFactor.a * inAlpha;
  alpha *= sampleMaterial(m, m.textures.x, inUv, vec4(1.0)).a;
  if (alpha < m.emissiveAlphaCutoff.w) discard;
}
