// A material's textures through their KHR_texture_transform, and its layers (clearcoat, sheen,
// specular) at a point: shared by the G-buffer raster and the traced hits so both shade alike.
// The includer may define RB_SAMPLE_MATERIAL(slot, uv) (the G-buffer's fragment shader samples
// with derivatives); compute shaders read mip 0.
#ifndef RB_MATERIAL_LAYERS_GLSL
#define RB_MATERIAL_LAYERS_GLSL
#include "include/brdf.glsl"
#include "include/octahedral.glsl"

#ifndef RB_SAMPLE_MATERIAL
#define RB_SAMPLE_MATERIAL(slot, uv) textureLod(textures[nonuniformEXT(slot)], uv, 0.0)
#endif

uint materialFlags(GpuMaterial m) { return floatBitsToUint(m.normalScaleThicknessFlags.z); }

// Where texture slot `slot` of `m` is read at `uv` (a material without transforms reads no
// transform).
vec2 textureUv(GpuMaterial m, int slot, vec2 uv) {
  if ((materialFlags(m) & RB_MATERIAL_UV_TRANSFORM) == 0u) return uv;
  GpuTextureTransform t = textureTransforms[slot];
  vec3 h = vec3(uv, 1.0);
  return vec2(dot(t.u.xyz, h), dot(t.v.xyz, h));
}

vec4 sampleMaterial(GpuMaterial m, int slot, vec2 uv, vec4 fallback) {
  return slot >= 0 ? RB_SAMPLE_MATERIAL(slot, textureUv(m, slot, uv)) : fallback;
}

// The layers at texture coordinate `uv` (`textured` false: the factors alone), the coat's
// normal being the surface's N (the G-buffer raster applies the coat's normal map).
Layers materialLayers(GpuMaterial m, vec2 uv, vec3 N, float ior, bool textured) {
  const vec4 one = vec4(1.0);
  Layers l = noLayers(N, ior);
  if ((materialFlags(m) & RB_MATERIAL_LAYERS) == 0u) return l;
  l.clearcoat = m.clearcoat.x * (textured ? sampleMaterial(m, m.layerTextures.x, uv, one).r : 1.0);
  l.clearcoatRoughness = clamp(m.clearcoat.y * (textured ? sampleMaterial(m, m.layerTextures.y, uv, one).g : 1.0), 0.0, 1.0);
  l.specular = m.clearcoat.w * (textured ? sampleMaterial(m, m.layerTextures.w, uv, one).a : 1.0);
  vec3 specularColor = m.specularColor.rgb * (textured ? sampleMaterial(m, m.layerTextures2.z, uv, one).rgb : vec3(1.0));
  l.specularF0 = min(l.specularF0 * specularColor, vec3(1.0));
  l.sheenColor = m.sheen.rgb * (textured ? sampleMaterial(m, m.layerTextures2.x, uv, one).rgb : vec3(1.0));
  l.sheenRoughness = m.sheen.w * (textured ? sampleMaterial(m, m.layerTextures2.y, uv, one).a : 1.0);
  return l;
}

// The G-buffer's encoding of the layers (R32G32B32A32_UINT; all zero: none):
// x unorm8 clearcoat, clearcoat roughness, 1 - specular, sheen roughness; y the coat's normal
// octahedron-encoded (snorm16 x2); z unorm8 sheen colour; w unorm8 sqrt of the dielectric F0
// colour and 1 in its last byte where the material sets one (else F0 follows the IOR).
uvec4 packLayers(Layers l, bool customF0) {
  return uvec4(packUnorm4x8(vec4(l.clearcoat, l.clearcoatRoughness, 1.0 - l.specular, l.sheenRoughness)),
               packSnorm2x16(octEncode(l.clearcoatNormal)), packUnorm4x8(vec4(l.sheenColor, 0.0)),
               customF0 ? packUnorm4x8(vec4(sqrt(l.specularF0), 1.0)) : 0u);
}

Layers unpackLayers(uvec4 p, vec3 N, float ior) {
  Layers l = noLayers(N, ior);
  vec4 x = unpackUnorm4x8(p.x);
  l.clearcoat = x.x;
  l.clearcoatRoughness = x.y;
  l.specular = 1.0 - x.z;
  l.sheenRoughness = x.w;
  if (l.clearcoat > 0.0) l.clearcoatNormal = octDecode(unpackSnorm2x16(p.y));
  l.sheenColor = unpackUnorm4x8(p.z).rgb;
  if (p.w != 0u) {
    vec3 root = unpackUnorm4x8(p.w).rgb;
    l.specularF0 = root * root;
  }
  return l;
}

bool customSpecularF0(GpuMaterial m) { return m.specularColor.w > 0.5; }

#endif
