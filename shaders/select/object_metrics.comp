#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_realtime_clock : require
// Per object: A, P, D, V = A*P/D, C = V*Q, R = (S*I + V)*K from its coverage, in the
// operation order of engine/src/select/metrics.cpp (precise: no contraction), which the
// tests check this against.
#include "include/bindings.glsl"
#include "include/stage_clock.glsl"

layout(local_size_x = RB_GROUP_SIZE) in;
layout(push_constant) uniform PushBlock { DrawPush push; };

float wide(uint lo, uint hi) {
  precise float v = float(hi) * 4294967296.0 + float(lo);
  return v;
}

void main() {
  stampStageStart();  // (where coverage kept the frame before's counts, the stage begins here)
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.objectMaterial.x) return;
  GpuCoverage cov = coverage[i];
  vec4 kqiS = objectParams[i].kqiS;
  uint width = frame.sizeLightsFrame.x, height = frame.sizeLightsFrame.y;
  float nearPlane = frame.cameraPositionNear.w;
  float distance = length(objects[i].boundsCenterRadius.xyz - frame.cameraPositionNear.xyz);
  precise float D = isnan(distance) ? 3.4e38 : clamp(distance, nearPlane, 3.4e38);
  uint pixelCount = cov.pixelsSumX.x;
  precise float A = 0.0, P = 0.0;
  if (pixelCount > 0u) {
    precise float pixels = float(pixelCount);
    A = pixels / (float(width) * float(height));
    precise float cx = (wide(cov.pixelsSumX.y, cov.pixelsSumX.z) / pixels + 0.5) / float(width) * 2.0 - 1.0;
    precise float cy = (wide(cov.pixelsSumX.w, cov.sumYHi.x) / pixels + 0.5) / float(height) * 2.0 - 1.0;
    P = clamp(1.0 - max(abs(cx), abs(cy)), 0.0, 1.0);
  }
  precise float V = A * P / D;
  precise float C = V * kqiS.y;
  precise float R = (kqiS.w * kqiS.z + V) * kqiS.x;
  bool candidate = pixelCount > 0u && kqiS.y > 0.0 && R > 0.0;
  objectRecords[i].apdv = vec4(A, P, D, V);
  objectRecords[i].crCandidatePixels = vec4(C, R, candidate ? 1.0 : 0.0, uintBitsToFloat(pixelCount));
}
