// The display transform: exposure, the ACES filmic fit of Narkowicz (2015), sRGB encoding.
// The frame's display image is written with it (storeComposed); the item error the trace passes measure is taken
// in the same space (GpuItemCost::error), since that is what a viewer and FLIP compare.
#ifndef RB_DISPLAY_GLSL
#define RB_DISPLAY_GLSL

vec3 acesNarkowicz(vec3 x) {
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec3 displayColor(vec3 hdr) { return linearToSrgb(acesNarkowicz(max(hdr, vec3(0.0)) * frame.exposure.x)); }

// The frame's pixel from its direct and indirect light: linear HDR (for EXR) and the display
// image (for the PNG). The compose pass's, or the lighting pass's where no trace pass follows it.
void storeComposed(ivec2 pixel, vec3 direct, vec3 indirect) {
  vec3 hdr = max(direct + indirect, vec3(0.0));
  imageStore(hdrImage, pixel, vec4(hdr, 1.0));
  imageStore(ldrImage, pixel, vec4(displayColor(hdr), 1.0));
}

// The display-space difference of two linear HDR colours: the mean absolute difference of
// their encoded channels, 0..1.
float displayError(vec3 a, vec3 b) {
  vec3 d = abs(displayColor(a) - displayColor(b));
  return (d.r + d.g + d.b) * (1.0 / 3.0);
}

#endif
