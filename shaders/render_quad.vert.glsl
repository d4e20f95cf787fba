#version 450
// QuadBatch (engine/render/quad_batch.hpp): one instance per quad, its two triangles made
// from gl_VertexIndex. Positions are target pixels (y down), depth 0 (near) to 1 (far).

layout(location = 0) in vec4 in_rect;  // min.xy, max.xy (pixels)
layout(location = 1) in vec4 in_uv;    // texture coordinates at min and max
layout(location = 2) in vec4 in_color; // linear RGBA (R8G8B8A8_UNORM)
layout(location = 3) in float in_depth;

layout(push_constant) uniform Push {
    vec2 inverse_target_size; // 1 / target width, 1 / target height
} push;

layout(location = 0) out vec2 out_uv;
layout(location = 1) out vec4 out_color;

const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    const vec2 corner = corners[gl_VertexIndex];
    const vec2 pixel = mix(in_rect.xy, in_rect.zw, corner);
    gl_Position = vec4(pixel * push.inverse_target_size * 2.0 - 1.0, in_depth, 1.0);
    out_uv = mix(in_uv.xy, in_uv.zw, corner);
    out_color = in_color;
}
