// The sources and weights of a reduced ray rate's fill (include/shadow_fill.glsl in the
// lighting pass, include/effect_fill.glsl in the fill pass after the effects pass): a pixel
// its item skipped this frame takes the weighted mean of what was traced around it on the
// same object (never another object's, nor an unlit pixel), across tiles: at 1/2 the four
// pixels beside it; at 1/4 the lattice points its rate traced among the 3x3 pixels around it
// (one to four); at 1/16 the four nearest, one per 4x4 block around it. Each traced neighbour
// is weighted by
//   distance  exp(-d^2 / 2), d in pixels (exp(-d^2 / 8) for 1/16's sparser samples);
//   depth     max(0, 1 - h / (RB_FILL_PLANE * r)), h the neighbour's distance from the
//             pixel's tangent plane, r the pixel's distance from the camera;
//   normal    max(0, n . n')^RB_FILL_NORMAL_POWER.
// The includer includes bindings.glsl, gbuffer.glsl, rates.glsl and probe.glsl.
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

// The distance weight of a traced neighbour `d` pixels from the pixel (1/16's sparser lattice
// wider).
float latticeNearness(ivec2 d, bool sixteenth) { return exp(float(d.x * d.x + d.y * d.y) * (sixteenth ? -0.125 : -0.5)); }

// Up to four traced neighbours of a skipped pixel and their weights (0: none there).
struct FillSources {
  ivec2 at[4];
  float weight[4];
  float total;
};

// 1/2's traced pixels beside a pixel it skipped.
const ivec2 kHalfRateNeighbours[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));

// The pixels around `pixel` that `rate` traced this frame and their distance weights (0: too
// far, or off screen); what was traced there, and on which object, is the caller's to check.
void fillLattice(ivec2 pixel, uint rate, out ivec2 at[4], out float near[4]) {
  uint frameIndex = frame.sizeLightsFrame.w;
  bool sixteenth = rate == RB_RATE_SIXTEENTH;
  // 1/4 and 1/16 trace a lattice of spacing 2 or 4: the four lattice points around the pixel.
  ivec2 offset = ivec2(sixteenth ? sixteenthOffset(frameIndex) : quarterOffset(frameIndex));
  int spacing = sixteenth ? 4 : 2;
  ivec2 below = pixel - ((pixel - offset) & (spacing - 1));
  for (int k = 0; k < 4; ++k) {
    ivec2 q = rate == RB_RATE_HALF ? pixel + kHalfRateNeighbours[k] : below + ivec2(k & 1, k >> 1) * spacing;
    ivec2 d = q - pixel;
    bool within = sixteenth || all(lessThanEqual(abs(d), ivec2(1)));  // 1/4: within the 3x3 pixels around it
    bool onScreen = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(uvec2(q), frame.sizeLightsFrame.xy));
    at[k] = q;
    near[k] = within && onScreen ? latticeNearness(d, sixteenth) : 0.0;
  }
}

// Whether a shadow item's pixel `q` lies in a tile it is traced in: a partial item (probe.glsl's
// selectionInTile) is traced on a share of its tiles, and outside them its shadow mask is an
// older frame's (read there, it drew the rate's lattice into a fly-through's ground).
bool shadowsTracedInTile(uint objectId, ivec2 q) {
  return (selectionInTile(objectId, 1u << RB_ITEM_SHADOWS, uvec2(q) / RB_TILE_SIZE) & (1u << RB_ITEM_SHADOWS)) != 0u;
}

// Whether the shadow pass wrote q's shadow mask this frame where its rate traces: past the
// stage's deadline it left -1 in the first layer instead (rt_shadows.comp's leaveShadows; no
// load where the deadline cut nothing).
bool shadowMaskWritten(ivec2 q) { return deadlineCut.x == 0u || imageLoad(shadowMask, ivec3(q, 0)).r >= 0.0; }

// The traced pixels around `pixel` on c's object and lit, and their weights for the shadow fill
// of c.
FillSources fillSources(ivec2 pixel, FillCentre c, uint rate) {
  FillSources f;
  float near[4];
  fillLattice(pixel, rate, f.at, near);
  f.total = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 q = f.at[k];
    bool source = near[k] > 0.0 && texelFetch(gObjectId, q, 0).r == c.objectId && texelFetch(gRoughTransIor, q, 0).a <= 0.5 &&
                  shadowsTracedInTile(c.objectId, q) && shadowMaskWritten(q);
    f.weight[k] = source ? near[k] * fillSimilarity(c, surfacePosition(q), surfaceNormal(q)) : 0.0;
    f.total += f.weight[k];
  }
  return f;
}

#endif
