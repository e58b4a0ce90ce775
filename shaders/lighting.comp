#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_ARB_shader_clock : require
#include "include/bindings.glsl"
layout(push_constant) uniform PushBlock { DrawPush push; };
#include "include/brdf.glsl"
#include "include/display.glsl"
#include "include/environment.glsl"
#include "include/gbuffer.glsl"
#include "include/item_stats.glsl"
#include "include/lights.glsl"
#include "include/shadows.glsl"
#include "include/probe.glsl"
#include "include/rates.glsl"
#include "include/shadow_fill.glsl"
#include "include/shadow_history.glsl"
#include "include/screen_pixel.glsl"
#include "include/env_fallback.glsl"

// Deferred direct lighting: every punctual light (GGX/Smith) with its visibility (the
// ray-traced shadow mask where traced, else the shadow maps, corrected where a reduced rate
// skipped the pixel), emissive, and diffuse ambient from the environment. Background pixels get
// the sky. Writes directImage, and the raster fallback for reflections and refractions
// (include/env_fallback.glsl) into reflectionImage and refractionImage, which the ray-traced
// passes replace for the paths they trace: one read of the G-buffer for both (as a pass of its
// own the fallback cost 1-7 ms more of a 90-170 ms frame at 1280x720 on lavapipe). With
// RB_RT_MEASURE_ITEMS, where shadows were traced it also lights the pixel with the shadow maps
// and adds the display-space difference (with the fallback's indirect term) to the object's
// shadow item. With RB_PASS_COMPOSE (no reflection or refraction is traced after it this frame)
// it also writes the composed frame, and the compose pass is left out: a full-screen pass of
// three reads and two writes a pixel less.
// With RB_PASS_BEHIND_GLASS it lights the opaque frame that glass shows behind it: the
// shadow maps alone, nothing measured.
layout(local_size_x = RB_TILE_SIZE, local_size_y = RB_TILE_SIZE, local_size_z = 1) in;

// The frame's pixel from the light this invocation stored, read back as the half-float images
// hold it (an invocation reads its own writes), as the compose pass reads it: packHalf2x16
// rounds otherwise than the image stores.
void composeStored(ivec2 pixel) { storeComposed(pixel, imageLoad(directImage, pixel).rgb, indirectLight(pixel)); }

void main() {
  ivec2 pixel = screenPixel();
  if (any(greaterThanEqual(uvec2(pixel), frame.sizeLightsFrame.xy))) return;
  Surface s;
  bool surface = readSurface(pixel, s);
  if (!surface || s.unlit) {
    imageStore(reflectionImage, pixel, vec4(0.0));
    imageStore(refractionImage, pixel, vec4(0.0));
    vec3 direct = surface ? s.baseColor : textureLod(envMap, viewDirection(pixel), 0.0).rgb;
    imageStore(directImage, pixel, vec4(direct, 1.0));
    if (composingPass()) composeStored(pixel);
    return;
  }
  vec3 V = normalize(frame.cameraPositionNear.xyz - s.position);
  // Behind glass the screen-space reflections and the geometric normal are not this surface's.
  bool behind = behindGlassPass();
  vec3 reflection = envReflection(s, V, behind ? ivec2(-1) : pixel, behind ? s.normal : surfaceGeometricNormal(pixel));
  imageStore(reflectionImage, pixel, vec4(reflection, 1.0));
  vec3 refraction = envTransmission(s, V);
  imageStore(refractionImage, pixel, vec4(refraction, 1.0));
  vec3 indirect = reflection + refraction;
  vec3 N = s.normal;
  vec3 color = s.emissive;
  // Ray-traced visibility replaces the shadow maps where the shadow pass traced: pixels of
  // objects whose shadow item is selected. Where the probe traced, it is measured, not shown.
  bool rtEnabled = (frame.rayTracing.x & RB_RT_SHADOWS) != 0u && !behind;
  Selection sel = selectionAt(s.objectId, pixel);
  bool rtShadows = rtEnabled && itemSelected(sel, RB_ITEM_SHADOWS);
  bool probed = rtEnabled && !rtShadows && itemProbed(sel, RB_ITEM_SHADOWS, pixel);
  // Measured where traced this frame: a reduced rate's other pixels are upsampled, not traced;
  // past the stage's deadline the shadow pass left the maps (include/fill_weights.glsl's shadowMaskWritten).
  bool traced = (probed || (rtShadows && itemTracedHere(sel, RB_ITEM_SHADOWS, pixel))) && shadowMaskWritten(pixel);
  bool measure = traced && measuringItems();
  // Where the item's reduced rate skipped the pixel, the maps are corrected by their error
  // where the point was last traced, else by their traced neighbours'.
  uint rate = itemRate(sel, RB_ITEM_SHADOWS);
  bool keepHistory = rtShadows && rate != RB_RATE_FULL && temporalFill();
  ShadowHistory past = noShadowHistory();
  if (keepHistory && !traced) past = previousShadowHistory(pixel, s.position, s.objectId, rate);
  bool carried = past.age != RB_HISTORY_NONE;
  FillSources fill;
  fill.total = 0.0;
  if (rtShadows && !traced && rate != RB_RATE_FULL && (!carried || frame.sizeLightsFrame.z > RB_SHADOW_HISTORY_LIGHTS))
    fill = fillSources(pixel, fillCentre(s.objectId, s.position, N), rate);
  uvec3 mapErrors = uvec3(0u);  // traced minus mapped where traced, packSnorm4x8's bytes, four lights to a word
  vec3 fallbackColor = s.emissive;  // with the shadow maps' visibility, when measuring
  for (uint i = 0u; i < frame.sizeLightsFrame.z; ++i) {
    GpuLight light = lights[i];
    vec3 L;
    float toLight, attenuation;
    if (!lightSample(light, s.position, L, toLight, attenuation) || dot(N, L) <= 0.0) continue;
    // The mask where traced (the rays' or the certain map's visibility), else the map's,
    // corrected by its error where the point was last traced (include/shadow_history.glsl),
    // else where the fill found traced neighbours (include/shadow_fill.glsl). A reduced rate's
    // traced pixel keeps the map's error for the history (its second mask layer holds the map's).
    float masked = traced ? imageLoad(shadowMask, ivec3(pixel, int(i))).r : -1.0;
    float mapped = rtShadows && traced && !measure ? 1.0 : shadowFromLight(light, s.position, N);
    bool remembered = i < RB_SHADOW_HISTORY_LIGHTS;
    if (keepHistory && traced && remembered) {
      uint byte = packSnorm4x8(vec4(masked - imageLoad(shadowMask, ivec3(pixel, mappedLayer(i))).r, 0.0, 0.0, 0.0)) << (8u * (i & 3u));
      uint word = i >> 2u;
      mapErrors.x |= word == 0u ? byte : 0u;
      mapErrors.y |= word == 1u ? byte : 0u;
      mapErrors.z |= word == 2u ? byte : 0u;
    }
    float correction = carried && remembered ? shadowHistoryError(past, i) : (fill.total > 0.0 ? shadowFillCorrection(fill, i, mapped) : 0.0);
    float visibility = traced ? masked : clamp(mapped + correction, 0.0, 1.0);
    vec3 unshadowed = shadeLayered(N, V, L, s.baseColor, s.metallic, s.roughness, s.transmission, s.layers) * light.colorIntensity.rgb * attenuation;
    color += unshadowed * visibility;
    fallbackColor += unshadowed * mapped;
  }
  if (keepHistory && (traced || carried)) {
    if (traced)
      past = ShadowHistory(mapErrors, 0u, s.position);
    else past.age += 1u;
    writeShadowHistory(pixel, past, s.objectId);
  }
  // Diffuse ambient: the roughest prefiltered level approximates irradiance / pi. The layers'
  // ambient (sheen, and the coat's reflection of its surroundings) is the same whether the
  // base's reflection is traced or not.
  vec3 irradiance = textureLod(envMap, N, float(RB_ENV_MIPS - 1)).rgb;
  vec3 coat = s.layers.clearcoat > 0.0 ? surroundings(s.position, coatReflection(s.layers, V), s.layers.clearcoatRoughness) : vec3(0.0);
  vec3 ambient = ambientLight(s.baseColor, s.metallic, s.transmission, s.layers, N, V, irradiance, coat);
  color += ambient;
  vec3 direct = probed ? fallbackColor + ambient : color;
  imageStore(directImage, pixel, vec4(direct, 1.0));
  if (composingPass()) composeStored(pixel);
  if (measuringItems() && !behind) {
    float error = measure ? displayError(color + indirect, fallbackColor + ambient + indirect) : 0.0;
    addItemCounts(measure ? s.objectId : RB_NO_OBJECT, uvec3(0u), uvec3(0u), errorUnits(vec3(error, 0.0, 0.0), pixel), uvec3(0u));
  }
}
