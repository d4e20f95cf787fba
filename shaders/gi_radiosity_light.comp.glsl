// The radiosity method's light image on the radiosity grid: the emission box-averaged over
// the grid texel, 0 in wall texels (walls are black, as in seed 003), plus feedback x last
// frame's radiosity (a bounce per frame). Mirrors reference_radiosity_light.
// camera_view.xy = grid origin; size = grid (w, h, pitch, -); parameters: RadiosityLightParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct RadiosityLightParams {
    int full_width, full_height, full_pitch; // the window-sized emission texture
    int scale;                               // window texels per grid texel
    float texels_per_unit;                   // grid texels per world unit
    float feedback;                          // 0: last frame's radiosity is not read
    int pad0, pad1;
};
#define GI_PASS_PARAMS RadiosityLightParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform samplerBuffer u_emission;
layout(binding = 3) uniform samplerBuffer u_previous; // the radiosity texture (read when feedback > 0)
layout(std430, binding = 4) writeonly buffer Out { uvec2 texels[]; } o_light;

#include "lantern/gi_shadow.glsl"

vec3 light(int i, int j) {
    vec2 c = grid_texel_center(i, j, pc.pass.texels_per_unit);
    if (is_wall(ivec2(floor(c)))) return vec3(0.0);
    int scale = pc.pass.scale;
    vec3 sum = vec3(0.0);
    int n = 0;
    for (int y = j * scale; y < min((j + 1) * scale, pc.pass.full_height); ++y)
        for (int x = i * scale; x < min((i + 1) * scale, pc.pass.full_width); ++x) {
            sum += texelFetch(u_emission, y * pc.pass.full_pitch + x).rgb;
            ++n;
        }
    vec3 value = sum / float(max(n, 1));
    if (pc.pass.feedback > 0.0) value += texelFetch(u_previous, texel_index(i, j)).rgb * pc.pass.feedback;
    return value;
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int j = o.y + int(r);
        if (j >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int i = o.x + k;
            if (i >= pc.size.x) break;
            o_light.texels[texel_index(i, j)] = pack_rgba16f(vec4(light(i, j), 1.0));
        }
    }
}
