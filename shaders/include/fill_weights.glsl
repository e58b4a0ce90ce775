// The weights of a reduced ray rate's fill (include/tile_fill.glsl, include/shadow_fill.glsl):
// a pixel its item skipped this frame takes the weighted mean of what was traced around it
// on the same object (never another object's), each traced neighbour weighted by
//   distance  exp(-d^2 / 2), d in pixels (exp(-d^2 / 8) for 1/16's sparser samples);
//   depth     max(0, 1 - h / (RB_FILL_PLANE * r)), h the neighbour's distance from the
//             pixel's tangent plane, r the pixel's distance from the camera;
//   normal    max(0, n . n')^RB_FILL_NORMAL_POWER.
// The includer includes bindings.glsl.
#ifndef RB_FILL_WEIGHTS_GLSL
#define RB_FILL_WEIGHTS_GLSL

#define RB_FILL_PLANE 0.02
#define RB_FILL_NORMAL_POWER 16  // (fillSimilarity squares four times)
// Below this summed weight no neighbour qualifies.
#define RB_FILL_MIN_WEIGHT 1e-3

struct FillCentre {
  uint objectId;
  vec3 position;
  vec3 normal;
  float planeScale;  // 1 / (RB_FILL_PLANE * distance from the camera)
};

FillCentre fillCentre(uint objectId, vec3 position, vec3 normal) {
  return FillCentre(objectId, position, normal, 1.0 / (RB_FILL_PLANE * max(length(position - frame.cameraPositionNear.xyz), 1e-6)));
}

// The depth and normal weights of a neighbour at `position` with `normal` for the fill of c.
float fillSimilarity(FillCentre c, vec3 position, vec3 normal) {
  float plane = max(0.0, 1.0 - abs(dot(c.normal, position - c.position)) * c.planeScale);
  float facing = max(dot(c.normal, normal), 0.0);
  facing *= facing;  // ^RB_FILL_NORMAL_POWER by squaring: four multiplies where pow is a log and an exp
  facing *= facing;
  facing *= facing;
  facing *= facing;
  return plane * facing;
}

#endif
