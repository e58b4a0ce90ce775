#version 460
// The editor's viewport: the composed frame with the chosen overlay blended per object (a
// tint per object ID, computed on the CPU from the frame's metrics), the picked object
// outlined, and the object ID under the cursor read back for picking.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba8) uniform readonly image2D frameLdr;
layout(set = 0, binding = 1) uniform usampler2D objectIds;
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D viewport;
layout(set = 0, binding = 3) readonly buffer Tints { vec4 tint[]; };  // rgb, blend weight
layout(set = 0, binding = 4) buffer Pick { uint pickedId; };
// The core's traced mask: per pixel, the effects traced there (1 shadows, 2 reflections, 4 refractions).
layout(set = 0, binding = 5, r32ui) uniform readonly uimage2D tracedMask;

layout(push_constant) uniform Push {
  ivec2 size;
  ivec2 pick;        // pixel whose object ID goes to pickedId (-1: none)
  uint objectCount;
  uint highlight;    // object outlined (0xFFFFFFFF: none)
  uint showTraced;   // 1: tint each pixel by the effects traced there
  uint pad;
} push;

const uint kNone = 0xFFFFFFFFu;

uint idAt(ivec2 p) { return texelFetch(objectIds, clamp(p, ivec2(0), push.size - 1), 0).r; }

vec3 effectColour(uint bits) {  // as editor/src/object_rows.cpp's
  vec3 c = vec3(0.0);
  if ((bits & 1u) != 0u) c += vec3(0.25, 0.45, 1.0);
  if ((bits & 2u) != 0u) c += vec3(1.0, 0.3, 0.25);
  if ((bits & 4u) != 0u) c += vec3(0.3, 1.0, 0.4);
  return c / max(1.0, max(c.r, max(c.g, c.b)));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, push.size))) return;
  vec4 c = imageLoad(frameLdr, p);
  uint id = idAt(p);
  if (id < push.objectCount) {
    vec4 t = tint[id];
    c.rgb = mix(c.rgb, t.rgb, t.a);
  }
  if (push.showTraced != 0u) {
    uint bits = imageLoad(tracedMask, p).r & 7u;
    if (bits != 0u) c.rgb = mix(c.rgb, effectColour(bits), 0.6);
  }
  if (push.highlight != kNone && id == push.highlight) {
    bool edge = idAt(p + ivec2(1, 0)) != id || idAt(p - ivec2(1, 0)) != id || idAt(p + ivec2(0, 1)) != id ||
                idAt(p - ivec2(0, 1)) != id;
    if (edge) c.rgb = vec3(1.0, 0.85, 0.1);
  }
  if (p == push.pick) pickedId = id;
  imageStore(viewport, p, vec4(c.rgb, 1.0));
}
