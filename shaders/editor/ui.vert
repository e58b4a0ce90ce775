#version 460
// The editor's UI (editor/src/ui_renderer.h): Dear ImGui's vertices, in pixels of its
// display, to clip space.
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 colour;

layout(push_constant) uniform Push {
  vec2 scale;      // 2 / display size
  vec2 translate;  // -1 - display origin * scale
} push;

layout(location = 0) out vec4 vColour;
layout(location = 1) out vec2 vUv;

void main() {
  vColour = colour;
  vUv = uv;
  gl_Position = vec4(position * push.scale + push.translate, 0.0, 1.0);
}
