// The pixel a screen pass's invocation shades. Lighting and behind_glass take
// DrawPush.objectMaterial as x the pass's mode, yz the origin and w the stride of the pixels
// they run over: the whole frame (0, 0, 1), or for the opaque frame behind glass every second
// pixel of the rectangle around the glass in view. The includer declares `push`.
#ifndef RB_SCREEN_PIXEL_GLSL
#define RB_SCREEN_PIXEL_GLSL

uint screenStride() { return max(push.objectMaterial.w, 1u); }
ivec2 screenPixel() { return ivec2(push.objectMaterial.yz + gl_GlobalInvocationID.xy * screenStride()); }
bool behindGlassPass() { return push.objectMaterial.x == RB_PASS_BEHIND_GLASS; }
// The lighting pass composes the frame itself (no trace pass follows it this frame).
bool composingPass() { return push.objectMaterial.x == RB_PASS_COMPOSE; }

#endif
