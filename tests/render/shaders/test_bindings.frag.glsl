#version 450
// Every binding kind a lit pass reads, in one fragment shader: a GI texture as a uniform
// texel buffer (RGBA16F, row-major, like engine::gi's textures), parameters in a uniform
// buffer, a texture through a combined image sampler.
// Columns left of params.size.y show the texel buffer times params.scale; the others show
// the texture at twice its size (texelFetch: exact).

layout(set = 0, binding = 0) uniform samplerBuffer gi;
layout(set = 0, binding = 1, std140) uniform Params {
    vec4 scale;
    ivec4 size; // x: texel buffer width, y: first texture column
} params;
layout(set = 0, binding = 2) uniform sampler2D sprite;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    if (p.x < params.size.y) {
        out_color = texelFetch(gi, p.y * params.size.x + p.x) * params.scale;
    } else {
        out_color = texelFetch(sprite, ivec2(p.x - params.size.y, p.y) / 2, 0);
    }
}
