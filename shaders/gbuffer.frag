#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"

layout(push_constant) uniform PushBlock { DrawPush push; };

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outBaseMetal;
layout(location = 2) out vec4 outRoughTransIor;
layout(location = 3) out vec4 outEmissive;
layout(location = 4) out uint outObjectId;
layout(location = 5) out uint outMaterialId;
layout(location = 6) out vec4 outPosition;
layout(location = 7) out uvec4 outLayers;

#define RB_SAMPLE_MATERIAL(slot, uv) texture(textures[nonuniformEXT(slot)], uv)
#include "include/material_layers.glsl"
#include "include/octahedral.glsl"

#include "include/normal_map.glsl"

// Perturbs N with a tangent-space normal map in the frame of screen-space derivatives. `uv`:
// the map's texture coordinates (after its transform).
vec3 perturbNormal(vec3 N, vec3 mapped, float scale, vec2 uv) {
  return perturbNormal(N, mapped, scale, dFdx(inWorld), dFdy(inWorld), dFdx(uv), dFdy(uv));
}

void main() {
  GpuMaterial m = materials[push.objectMaterial.y];
  uint flags = floatBitsToUint(m.normalScaleThicknessFlags.z);
  vec4 base = m.baseColorFactor * inColor * sampleMaterial(m, m.textures.x, inUv, vec4(1.0));
  if ((flags & RB_MATERIAL_ALPHA_MASK) != 0u && base.a < m.emissiveAlphaCutoff.w) discard;

  vec3 N = normalize(inNormal);
  // Two-sided lighting faces the viewer; one-sided back faces keep their normal.
  if (!gl_FrontFacing && (flags & RB_MATERIAL_DOUBLE_SIDED) != 0u) N = -N;
  vec3 surfaceN = N;  // the coat's normal map perturbs the surface's, not the base's map
  if (m.textures.z >= 0) {
    vec2 uv = textureUv(m, m.textures.z, inUv);
    N = perturbNormal(N, texture(textures[nonuniformEXT(m.textures.z)], uv).xyz, m.normalScaleThicknessFlags.x, uv);
  }

  vec4 mr = sampleMaterial(m, m.textures.y, inUv, vec4(1.0));
  float roughness = clamp(m.metallicRoughnessTransmissionIor.y * mr.g, 0.0, 1.0);
  float metallic = clamp(m.metallicRoughnessTransmissionIor.x * mr.b, 0.0, 1.0);
  vec3 emissive = m.emissiveAlphaCutoff.rgb * sampleMaterial(m, m.textures.w, inUv, vec4(1.0)).rgb;
  Layers layers = materialLayers(m, inUv, N, m.metallicRoughnessTransmissionIor.w, true);
  layers.clearcoatNormal = surfaceN;
  if ((flags & RB_MATERIAL_LAYERS) != 0u && m.layerTextures.z >= 0) {
    vec2 uv = textureUv(m, m.layerTextures.z, inUv);
    layers.clearcoatNormal = perturbNormal(surfaceN, texture(textures[nonuniformEXT(m.layerTextures.z)], uv).xyz, m.clearcoat.z, uv);
  }

  outNormal = vec4(N, !gl_FrontFacing && (flags & RB_MATERIAL_DOUBLE_SIDED) == 0u ? 1.0 : 0.0);  // w: seen from inside
  outBaseMetal = vec4(base.rgb, metallic);
  outRoughTransIor = vec4(roughness, m.metallicRoughnessTransmissionIor.z, m.metallicRoughnessTransmissionIor.w,
                          (flags & RB_MATERIAL_UNLIT) != 0u ? 1.0 : 0.0);
  outEmissive = vec4(emissive, (flags & RB_MATERIAL_LAYERS) != 0u ? 1.0 : 0.0);  // a: read the layers
  outObjectId = objects[push.objectMaterial.x].ids.x;
  outMaterialId = push.objectMaterial.y;
  // The triangle's plane normal from screen derivatives (exact for the plane: every sample
  // of a quad, helpers included, lies on it), turned towards the viewer.
  vec3 ng = normalize(cross(dFdx(inWorld), dFdy(inWorld)));
  if (dot(ng, frame.cameraPositionNear.xyz - inWorld) < 0.0) ng = -ng;
  outPosition = vec4(inWorld, uintBitsToFloat(packSnorm2x16(octEncode(ng))));
  outLayers = (flags & RB_MATERIAL_LAYERS) != 0u ? packLayers(layers, customSpecularF0(m)) : uvec4(0u);
}
