#version 460
#extension GL_GOOGLE_include_directive : require
#include "include/bindings.glsl"
#include "include/brdf.glsl"
#include "include/sky.glsl"

// GGX-prefiltered environment (Karis 2013 split sum) for mip push.objectMaterial.x, with
// roughness = mip / (mips - 1). Filtered importance sampling (Krivanek & Colbert 2008):
// each sample reads the sky mip whose texel matches the sample's solid angle, which keeps
// 64 samples free of fireflies around the sun.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

vec2 hammersley(uint i, uint n) {
  uint b = bitfieldReverse(i);
  return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}

void main() {
  uint mip = push.objectMaterial.x;
  uint size = max(RB_ENV_SIZE >> mip, 1u);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  vec3 N = cubeDirection(id.z, id.xy, size);
  float roughness = float(mip) / float(RB_ENV_MIPS - 1);
  vec3 result;
  if (mip == 0u) {
    result = textureLod(skyMap, N, 0.0).rgb;
  } else {
    float alpha = roughness * roughness;
    vec3 up = abs(N.y) < 0.999 ? vec3(0, 1, 0) : vec3(1, 0, 0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    float texelSolidAngle = 4.0 * PI / (6.0 * float(RB_ENV_SIZE * RB_ENV_SIZE));
    for (uint i = 0u; i < RB_ENV_PREFILTER_SAMPLES; ++i) {
      vec2 xi = hammersley(i, RB_ENV_PREFILTER_SAMPLES);
      float phi = 2.0 * PI * xi.x;
      float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
      float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
      vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
      vec3 L = reflect(-N, H);
      float NoL = dot(N, L);
      if (NoL <= 0.0) continue;
      // V = N: pdf(L) = D(H) / 4.
      float pdf = dGgx(cosTheta, max(alpha, 1e-3)) * 0.25;
      float sampleSolidAngle = 1.0 / (float(RB_ENV_PREFILTER_SAMPLES) * pdf + 1e-6);
      float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0, float(RB_ENV_MIPS - 1));
      sum += textureLod(skyMap, L, lod).rgb * NoL;
      weight += NoL;
    }
    result = sum / max(weight, 1e-6);
  }
  imageStore(envStorage[mip], ivec3(id), vec4(result, 1.0));
}
