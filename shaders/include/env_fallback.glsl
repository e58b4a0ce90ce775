// The raster fallback for reflections and refractions, per path: in the reflected direction
// the screen-space reflection, else the surroundings (the reflection probe around the
// surface, else the sky; split-sum specular), and through the surface the opaque frame behind it (screen-space transmission,
// else the surroundings; Snell, with
// KHR_materials_volume attenuation over the thickness). The lighting pass writes their
// sum; the trace pass keeps the path it does not trace as this exactly, and measures the
// path it traces against it.
#ifndef RB_ENV_FALLBACK_GLSL
#define RB_ENV_FALLBACK_GLSL
#include "include/environment.glsl"

// The split-sum weights of the surface's reflection and transmission (brdf.glsl).
void envWeights(Surface s, vec3 N, vec3 V, out vec3 reflectWeight, out vec3 transmitWeight) {
  layeredEnvWeights(s.baseColor, s.metallic, s.roughness, s.transmission, s.layers, N, V, reflectWeight, transmitWeight);
}

// The reflection at `pixel` (geometric normal ng, which turns the mirror ray back above the
// surface as the tracer does): the screen-space reflection where it found the reflected surface
// (by its confidence), else the surroundings, weighted as the tracer weights its ray (the
// shading normal on the viewer's side). Seen from inside a one-sided model (the camera within
// it), the mirror ray meets the model's own inside, not the surroundings: it is taken to show
// the surroundings reflected once more by the same material (the tracer's first hit there is
// lit by its environment reflection alone, the lights being shut out). Read as if outside,
// `none`'s FLIP against `all` on the earlier fly-throughs that entered Suzanne and the
// WaterBottle was 0.219 / 0.146 (0.062 / 0.128 with the weights on the viewer's side, 0.012 /
// 0.081 reading black there, 0.006 / 0.009 as now). A pixel of -1 (the opaque frame behind
// glass, whose surfaces neither the screen-space pass nor the G-buffer saw: ng is not read)
// takes the surroundings alone, along the unturned mirror ray.
vec3 envReflection(Surface s, vec3 V, ivec2 pixel, vec3 ng) {
  bool onScreen = pixel.x >= 0;
  vec3 R = onScreen ? mirrorDirection(V, s.normal, ng) : reflect(-V, s.normal);
  vec3 reflectWeight, transmitWeight;
  envWeights(s, onScreen ? viewerSideNormal(s.normal, ng) : s.normal, V, reflectWeight, transmitWeight);
  vec3 incoming = surroundings(s.position, R, s.roughness);
  if (onScreen && s.seenFromInside) incoming *= reflectWeight;
  if (onScreen && ssrReady() && s.roughness < frame.ssr.y) {
    vec4 screen = imageLoad(ssrImage, pixel);
    incoming = mix(incoming, screen.rgb, screen.a);
  }
  return incoming * reflectWeight;
}

// glTF's thickness is in the mesh's space, so the node's transform scales it: the faces of a
// slab of local thickness t along the local normal lie t·|Mᵀn| apart for the world normal n.
float worldThickness(Surface s, float thickness) {
  return thickness * length(transpose(mat3(objects[s.objectId].model)) * s.normal);
}

// What a transmissive surface shows behind it, as Filament and three.js do it: the opaque
// frame (lit before the transmissive surfaces were drawn) where the ray leaves the volume,
// projected to the screen, blurred by a mip from roughness and IOR; the surroundings in the
// ray's direction where that point is off the screen or the opaque frame there lies in front
// of the surface. A thin wall (the exit point is the surface's) is not blurred: the tracer
// passes the view ray through it as it is, one ray and no roughness lobe, and the blur made
// the fallback disagree with it on rough thin glass (TransmissionTest's FLIP against `all`
// 0.0758 / 0.1063 blurred, 0.0588 / 0.0975 sharp; volumes moved by under 0.0001).
vec3 behindSurface(Surface s, vec3 exitPoint, vec3 exitDir) {
  float blur = exitPoint == s.position ? 0.0 : s.roughness;
  if (behindGlassReady()) {
    vec4 clip = frame.viewProj * vec4(exitPoint, 1.0);
    vec2 uv = clip.xy / max(clip.w, 1e-6) * 0.5 + 0.5;
    if (clip.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
      vec2 size = vec2(textureSize(behindGlass, 0));
      float behind = texelFetch(behindGlass, min(ivec2(uv * size), ivec2(size) - 1), 0).a;
      if (behind > length(s.position - frame.cameraPositionNear.xyz)) {
        float lod = log2(max(size.x, size.y)) * blur * clamp(2.0 * s.ior - 2.0, 0.0, 1.0);
        return textureLod(behindGlass, uv, lod).rgb;
      }
    }
  }
  return surroundings(exitPoint, exitDir, blur);
}

// Zero for opaque surfaces.
vec3 envTransmission(Surface s, vec3 V) {
  float transmission = s.transmission * (1.0 - s.metallic);
  if (transmission <= 0.0) return vec3(0.0);
  vec3 N = s.normal;
  GpuMaterial m = materials[s.materialId];
  vec3 T = refract(-V, N, 1.0 / max(s.ior, 1.0));
  float thickness = worldThickness(s, m.normalScaleThicknessFlags.y);
  // Thick volumes bend the ray back on exit through a parallel surface: the exit direction
  // equals -V, offset; thin walls let the view ray through unbent (glTF's thin-walled model,
  // as the tracer does).
  vec3 dir = -V;
  if (thickness > 0.0 && dot(T, T) > 0.0) dir = normalize(mix(-V, T, 0.5));
  // The refracted ray crosses the volume's thickness at its angle to the inward normal; a thin
  // wall lets the view ray through.
  float distanceInside = thickness / max(dot(T, -N), 0.05);
  vec3 exitPoint = thickness > 0.0 && dot(T, T) > 0.0 ? s.position + T * distanceInside : s.position;
  vec3 transmitted = behindSurface(s, exitPoint, dir);
  if (m.attenuationColorDistance.w > 0.0 && thickness > 0.0)
    transmitted *= pow(m.attenuationColorDistance.rgb, vec3(distanceInside / m.attenuationColorDistance.w));
  vec3 reflectWeight, transmitWeight;
  envWeights(s, s.normal, V, reflectWeight, transmitWeight);
  if (thickness <= 0.0 && (objects[s.objectId].ids.w & RB_OBJECT_CLOSED_THIN_GLASS) != 0u) {
    // A closed thin shell (a glass bubble): the view ray leaves through its far wall, which
    // tints what passes once more and reflects the surroundings, as the tracer's ray does. The
    // far wall is taken as a sphere's: the chord's ends mirror each other across the plane
    // normal to the ray, so the ray meets it at the same angle (the same weights).
    vec3 farNormal = N - 2.0 * dot(N, V) * V;
    transmitted = transmitted * transmitWeight + surroundings(s.position, reflect(-V, farNormal), s.roughness) * reflectWeight;
  }
  return transmitted * transmitWeight;  // the base colour, the transmitted share, through the layers
}

// What a traced path's radiance is weighted by at the surface (rt_effects.comp, and the
// upsample for the pixels it fills): from the exact point `p` and geometric normal `ng`, the
// shading normal N turned to the viewer's side, the view direction V, the split-sum specular
// weight of the reflection and the transmitted share of the refraction.
void tracedPathWeights(Surface s, vec3 p, vec3 ng, out vec3 N, out vec3 V, out vec3 specularWeight, out vec3 transmitWeight) {
  V = normalize(frame.cameraPositionNear.xyz - p);
  N = viewerSideNormal(s.normal, ng);
  envWeights(s, N, V, specularWeight, transmitWeight);
}

#endif
