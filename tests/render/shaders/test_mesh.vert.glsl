#version 450
// Indexed meshes with per-vertex attributes: positions in target pixels, 8-bit colours.

layout(location = 0) in vec2 in_position;
layout(location = 1) in vec4 in_color;

layout(push_constant) uniform Push {
    vec2 inverse_target_size;
} push;

layout(location = 0) out vec4 out_color;

void main() {
    gl_Position = vec4(in_position * push.inverse_target_size * 2.0 - 1.0, 0.0, 1.0);
    out_color = in_color;
}
