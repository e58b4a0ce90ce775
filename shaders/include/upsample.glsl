// The joint bilateral upsample of reduced ray rates (include/rates.glsl): a pixel its item did
// not trace this frame takes the weighted mean of the values traced this frame within
// RB_UPSAMPLE_RADIUS pixels on the same object (never another object's), each weighted by
//   distance  exp(-d^2 / 2), d in pixels;
//   depth     max(0, 1 - h / (RB_UPSAMPLE_PLANE * r)), h the neighbour's distance from the
//             pixel's tangent plane, r the pixel's distance from the camera;
//   normal    max(0, n . n')^RB_UPSAMPLE_NORMAL_POWER.
// A radius of 1 holds four traced pixels at 1/2 and one to four at 1/4 (every 2x2 quad holds
// one); radius 2 found more near an object's edge at 2.8 times the cost. Where no neighbour
// qualifies the fallback stays. The includer includes bindings.glsl and gbuffer.glsl.
#ifndef RB_UPSAMPLE_GLSL
#define RB_UPSAMPLE_GLSL

#define RB_UPSAMPLE_RADIUS 1
#define RB_UPSAMPLE_PLANE 0.02
#define RB_UPSAMPLE_NORMAL_POWER 16.0
// Below this summed weight no neighbour qualifies.
#define RB_UPSAMPLE_MIN_WEIGHT 1e-3

struct UpsampleCentre {
  uint objectId;
  vec3 position;
  vec3 normal;
  float planeScale;  // 1 / (RB_UPSAMPLE_PLANE * distance from the camera)
};

UpsampleCentre upsampleCentre(ivec2 pixel, uint objectId) {
  vec3 p = texelFetch(gPosition, pixel, 0).xyz;
  vec3 n = normalize(texelFetch(gNormal, pixel, 0).xyz);
  return UpsampleCentre(objectId, p, n, 1.0 / (RB_UPSAMPLE_PLANE * max(length(p - frame.cameraPositionNear.xyz), 1e-6)));
}

// The object at `pixel` when its item `effect` is selected at a reduced rate that skips the
// pixel this frame (and the pixel is lit), else RB_NO_OBJECT: the upsample's cheap first test.
uint pendingObject(ivec2 pixel, uint effect) {
  uint id = texelFetch(gObjectId, pixel, 0).r;
  if (id == RB_NO_OBJECT || !itemSelected(id, effect)) return RB_NO_OBJECT;
  uint rate = itemRate(id, effect);
  if (rate == RB_RATE_FULL || rateTraces(rate, pixel) || texelFetch(gRoughTransIor, pixel, 0).a > 0.5) return RB_NO_OBJECT;
  return id;
}

// The weight of neighbour `q` at `offset` from the centre (0: another object or off screen).
float upsampleWeight(UpsampleCentre c, ivec2 q, ivec2 offset) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), frame.sizeLightsFrame.xy))) return 0.0;
  if (texelFetch(gObjectId, q, 0).r != c.objectId || texelFetch(gRoughTransIor, q, 0).a > 0.5) return 0.0;  // unlit: nothing traced
  vec3 p = texelFetch(gPosition, q, 0).xyz;
  vec3 n = normalize(texelFetch(gNormal, q, 0).xyz);
  float plane = max(0.0, 1.0 - abs(dot(c.normal, p - c.position)) * c.planeScale);
  float facing = pow(max(dot(c.normal, n), 0.0), RB_UPSAMPLE_NORMAL_POWER);
  return exp(-0.5 * float(dot(offset, offset))) * plane * facing;
}

#endif
