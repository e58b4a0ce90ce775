// The min-depth pyramid the screen-space reflections march in (Hi-Z; depth_pyramid.comp builds
// it, ssr.comp marches it): level 0 is the G-buffer's depth itself, the pyramid image's mip m
// holds level m + 1. The includer includes bindings.glsl.
#ifndef RB_DEPTH_PYRAMID_GLSL
#define RB_DEPTH_PYRAMID_GLSL

float pyramidDepth(ivec2 cell, int level) { return level == 0 ? texelFetch(gDepth, cell, 0).r : texelFetch(depthPyramid, cell, level - 1).r; }

#endif
