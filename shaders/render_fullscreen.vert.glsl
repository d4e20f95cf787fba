#version 450
// One triangle covering the whole target (draw 3 vertices, no vertex buffer): the vertex
// stage of full-screen passes such as the lit pass that reads the GI textures.

layout(location = 0) out vec2 out_uv; // 0..1 across the target, (0, 0) at the top-left

void main() {
    const vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    out_uv = uv;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
