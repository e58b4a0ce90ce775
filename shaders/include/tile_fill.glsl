// The fill of reduced ray rates (include/rates.glsl), inside the trace passes: after the
// pixels a rate traces this frame have traced, each shares what it traced in the workgroup's
// shared memory, the workgroup waits at a barrier, and every pixel its item skipped this frame
// takes the weighted mean of the values traced around it (fillOffset) in the same 8x8 tile on
// the same object (never another object's), each weighted by
//   distance  exp(-d^2 / 2), d in pixels (exp(-d^2 / 8) for 1/16's sparser samples);
//   depth     max(0, 1 - h / (RB_FILL_PLANE * r)), h the neighbour's distance from the
//             pixel's tangent plane, r the pixel's distance from the camera;
//   normal    max(0, n . n')^RB_FILL_NORMAL_POWER.
// For 1/2 and 1/4 the 3x3 pixels around it, which always hold its own 2x2 quad (1/4 traces one
// pixel of it, 1/2 two); for 1/16 the tile's four pixels it traced, one per 4x4 block, up to
// three pixels away on each axis. Neighbours across the tile's edge are left out (a pass of
// its own reading them from images cost as much as the tracing it saved on lavapipe). Where no
// neighbour qualifies the fallback stays. The includer includes bindings.glsl.
#ifndef RB_TILE_FILL_GLSL
#define RB_TILE_FILL_GLSL

#define RB_FILL_PLANE 0.02
#define RB_FILL_NORMAL_POWER 16  // (fillWeight squares four times)
// Below this summed weight no neighbour qualifies.
#define RB_FILL_MIN_WEIGHT 1e-3
#define RB_TILE_PIXELS (RB_TILE_SIZE * RB_TILE_SIZE)

// Per pixel of the tile: the object it traced for (RB_NO_OBJECT: nothing to share), where.
shared uint fillObject[RB_TILE_PIXELS];
shared vec3 fillPosition[RB_TILE_PIXELS];
shared vec3 fillNormal[RB_TILE_PIXELS];

// Whether the trace passes fill this frame (the pipeline's specialization, set where RB_RT_RATES
// is): uniform, so the barrier stays in uniform control flow, and the plain pipeline's
// compiler drops the fill, its barrier and its shared memory.
layout(constant_id = RB_FILL_CONSTANT_ID) const bool rbFill = false;
bool fillsInPass() { return rbFill; }

uint fillIndex(ivec2 pixel) {
  ivec2 a = pixel & (RB_TILE_SIZE - 1);
  return uint(a.y * RB_TILE_SIZE + a.x);
}

// Each invocation clears its own pixel's slot before its pass writes anything.
void clearFillSlot(ivec2 pixel) { fillObject[fillIndex(pixel)] = RB_NO_OBJECT; }

void shareFillSource(ivec2 pixel, uint objectId, vec3 position, vec3 normal) {
  uint i = fillIndex(pixel);
  fillObject[i] = objectId;
  fillPosition[i] = position;
  fillNormal[i] = normal;
}

struct FillCentre {
  uint objectId;
  vec3 position;
  vec3 normal;
  float planeScale;  // 1 / (RB_FILL_PLANE * distance from the camera)
};

FillCentre fillCentre(uint objectId, vec3 position, vec3 normal) {
  return FillCentre(objectId, position, normal, 1.0 / (RB_FILL_PLANE * max(length(position - frame.cameraPositionNear.xyz), 1e-6)));
}

// The neighbours a pixel's fill reads at `rate`: how many, and the k-th one's offset.
int fillCandidates(uint rate) { return rate == RB_RATE_SIXTEENTH ? 4 : 9; }
ivec2 fillOffset(uint rate, ivec2 pixel, int k) {
  if (rate != RB_RATE_SIXTEENTH) return ivec2(k % 3 - 1, k / 3 - 1);
  return (pixel & ~(RB_TILE_SIZE - 1)) + ivec2(sixteenthOffset(frame.sizeLightsFrame.w)) + ivec2(k & 1, k >> 1) * 4 - pixel;
}

// The slot of the neighbour at `offset` from `pixel` and its weight; 0 where the item's `rate`
// did not trace it this frame (1 to 4 of 1/4's 9 are left: tested first, the cheap way, as
// shared memory is slow to gather from on lavapipe), outside the tile, on another object or
// where nothing was shared.
float fillWeight(FillCentre c, uint rate, ivec2 pixel, ivec2 offset, out uint slot) {
  ivec2 a = (pixel & (RB_TILE_SIZE - 1)) + offset;
  slot = 0u;
  if (!rateTraces(rate, pixel + offset)) return 0.0;
  if (any(lessThan(a, ivec2(0))) || any(greaterThanEqual(a, ivec2(RB_TILE_SIZE)))) return 0.0;
  slot = uint(a.y * RB_TILE_SIZE + a.x);
  if (fillObject[slot] != c.objectId) return 0.0;
  float plane = max(0.0, 1.0 - abs(dot(c.normal, fillPosition[slot] - c.position)) * c.planeScale);
  float facing = max(dot(c.normal, fillNormal[slot]), 0.0);
  facing *= facing;  // ^RB_FILL_NORMAL_POWER by squaring: four multiplies where pow is a log and an exp
  facing *= facing;
  facing *= facing;
  facing *= facing;
  int d2 = offset.x * offset.x + offset.y * offset.y;
  float near = rate == RB_RATE_SIXTEENTH ? exp(-0.125 * float(d2)) : (d2 == 0 ? 1.0 : (d2 == 1 ? 0.60653066 : 0.36787944));  // exp(-d2 / 2)
  return near * plane * facing;
}

#endif
