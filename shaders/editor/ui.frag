#version 460
// The editor's UI: the vertex colour times the font atlas's coverage (ImGui's own shader,
// with the atlas as one R8 channel).
layout(set = 0, binding = 0) uniform sampler2D atlas;

layout(location = 0) in vec4 vColour;
layout(location = 1) in vec2 vUv;
layout(location = 0) out vec4 outColour;

void main() { outColour = vec4(vColour.rgb, vColour.a * texture(atlas, vUv).r); }
