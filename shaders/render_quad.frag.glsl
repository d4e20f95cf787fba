#version 450
// QuadBatch: the quad's texture (a 1x1 white one for plain colour) times its colour.

layout(set = 0, binding = 0) uniform sampler2D quad_texture;

layout(location = 0) in vec2 in_uv;
layout(location = 1) in vec4 in_color;

layout(location = 0) out vec4 out_color;

void main() {
    out_color = texture(quad_texture, in_uv) * in_color;
}
