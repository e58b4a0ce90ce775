#version 460
layout(push_constant) uniform Push {
  mat4 viewProj;
  vec4 baseColor;
  vec4 material;
  vec4 emissiveUnlit;
  uvec4 ids;
  vec4 camera;
} push;

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inColor;

layout(location = 0) out vec4 outNormal;         // world shading normal; w: 1 seen from inside
layout(location = 1) out vec4 outBaseMetal;      // base colour, metallic
layout(location = 2) out vec4 outRoughTransIor;  // roughness, transmission, IOR, unlit
layout(location = 3) out vec4 outEmissive;
layout(location = 4) out uint outObjectId;
layout(location = 5) out uint outMaterialId;
layout(location = 6) out vec4 outPosition;       // world position; w: packed plane normal

// raybudget's packing of the plane normal: octahedral (Cigolle et al. 2014), packSnorm2x16.
vec2 octEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.xy;
  if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return e;
}

void main() {
  vec3 N = normalize(inNormal);
  if (!gl_FrontFacing && push.ids.z != 0u) N = -N;  // two-sided surfaces face the viewer
  outNormal = vec4(N, !gl_FrontFacing && push.ids.z == 0u ? 1.0 : 0.0);  // the back of a one-sided surface
  outBaseMetal = vec4(push.baseColor.rgb * inColor.rgb, clamp(push.material.x, 0.0, 1.0));
  outRoughTransIor = vec4(clamp(push.material.y, 0.0, 1.0), push.material.z, push.material.w, push.emissiveUnlit.w);
  outEmissive = vec4(push.emissiveUnlit.rgb, 0.0);
  outObjectId = push.ids.x;
  outMaterialId = push.ids.y;
  vec3 ng = normalize(cross(dFdx(inWorld), dFdy(inWorld)));
  if (dot(ng, push.camera.xyz - inWorld) < 0.0) ng = -ng;
  outPosition = vec4(inWorld, uintBitsToFloat(packSnorm2x16(octEncode(ng))));
}
