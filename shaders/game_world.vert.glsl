#version 450
// The game's world renderer (game/include/lantern/game/world_renderer.hpp): one box face per
// 6 vertices (two triangles) of a plain, non-instanced draw; the face's box is pulled from the
// box texel buffer (three RGBA32F texels per box) at gl_VertexIndex / 6. The face is the specialisation constant FACE (0 +x,
// 1 -x, 2 +z, 3 -z, 4 top): one pipeline per face, so that the fragment stage's normal is a
// constant and the shading library's routing folds to the branches that face can take
// (lavapipe runs both sides of every branch). The unit-box mesh is the constant tables below,
// indexed by FACE and gl_VertexIndex % 6. The CPU lists only the boxes whose face is in the mask and turned
// towards the camera; the same test here collapses any other face to one point outside the
// view (a degenerate triangle, culled before rasterisation).

#extension GL_GOOGLE_include_directive : require
#define LANTERN_GAME_WORLD_GRID_LOOKUP
#include "lantern/game_world.glsl"

// BoxInstance: texel 3i xyz centre, w material; 3i+1 xyz half extents, w face mask;
// 3i+2 rgb colour, w emissive strength.
layout(set = 0, binding = 18) uniform samplerBuffer u_boxes;


layout(location = 0) out vec3 out_position;     // world position
layout(location = 1) flat out int out_material;
layout(location = 2) flat out vec4 out_color;   // rgb colour, a emissive
layout(location = 3) flat out vec3 out_box_min; // the box, to keep interpolated positions on it
layout(location = 4) flat out vec3 out_box_max;
layout(location = 5) flat out vec3 out_face_light; // WALL_TOP_PER_FACE: the top's light
layout(location = 6) flat out vec3 out_probe_light; // lit_probes, texel_lit: what the baked light's direction adds
layout(location = 8) flat out vec3 out_face_bounce; // WALL_TOP_PER_FACE: the bounce part of out_face_light
layout(location = 7) flat out ivec4 out_texel; // texel_lit (TEXEL): atlas index of the face's texel (0, 0), texture size, face width, height

const vec3 face_normal[5] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, 1, 0));
const vec3 face_u[5] = vec3[](vec3(0, 0, 1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0), vec3(1, 0, 0));
const vec3 face_v[5] = vec3[](vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 0, 1));
const vec2 quad[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));

// The GI's live probes at ground point p, added to c: bilinear between the four probes around
// p, over those in open ground (bake::interpolate_probes' rule).
void add_live_probes(vec2 p, inout vec3 c[5]) {
    const ivec2 count = ivec2(pc.probes.z & 0xFFFF, pc.probes.z >> 16);
    const vec2 g = (p - 0.5 - vec2(pc.probes.xy)) / 2.0;
    const ivec2 i0 = ivec2(floor(g));
    const vec2 f = g - vec2(i0);
    vec3 sum[5] = vec3[5](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        const ivec2 i = i0 + ivec2(k & 1, k >> 1);
        if (i.x < 0 || i.y < 0 || i.x >= count.x || i.y >= count.y) continue;
        const int base = i.y * pc.probes.w + 5 * i.x;
        const vec4 a0 = texelFetch(u_probes, base);
        if (a0.a < 0.5) continue; // in a wall
        const float w = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
        sum[0] += a0.rgb * w;
        for (int h = 1; h < 5; ++h) sum[h] += texelFetch(u_probes, base + h).rgb * w;
        weight += w;
    }
    if (weight > 0.0)
        for (int h = 0; h < 5; ++h) c[h] += sum[h] / weight;
}

// What the light probes (world_renderer.hpp ProbeRecord at texel `base` of u_boxes: the baked
// light's, and with its `live` texel the GI's live probes at its anchor) add to a side face of
// normal n: max(pi E(phi), 0) - a0 (the GI textures give the a0 part).
vec3 probe_face_light(int base, vec3 n) {
    const float pi = 3.14159265;
    const float phi = atan(n.z, n.x);
    vec3 c[5];
    for (int h = 0; h < 5; ++h) c[h] = texelFetch(u_boxes, base + h).rgb;
    const vec4 live = texelFetch(u_boxes, base + 5);
    if (HAS_GI && live.z > 0.5 && pc.probes.w > 0) add_live_probes(live.xy, c);
    const vec3 e = c[0] / pi + (c[1] * cos(phi) + c[2] * sin(phi)) * 0.5 +
                   (c[3] * cos(2.0 * phi) + c[4] * sin(2.0 * phi)) * (2.0 / (3.0 * pi));
    return max(pi * e, vec3(0.0)) - c[0];
}

void main() {
    const int face = FACE;
    const int box = gl_VertexIndex / 6;
    const vec4 in_center_material = texelFetch(u_boxes, 3 * box);
    const vec4 in_half_mask = texelFetch(u_boxes, 3 * box + 1);
    const vec4 in_color_emissive = texelFetch(u_boxes, 3 * box + 2);
    const vec2 corner = quad[gl_VertexIndex - 6 * box];
    const vec3 n = face_normal[face];
    const vec3 center = in_center_material.xyz, half_extent = max(in_half_mask.xyz, vec3(0.0));
    const int mask = int(in_half_mask.w + 0.5);
    const vec3 face_point = center + half_extent * n;
    const bool drawn = ((mask >> face) & 1) != 0 && dot(pc.camera.xyz - face_point, n) > 0.0;
    if (!drawn) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // every vertex of the face here: zero area, outside
        return;
    }
    const vec3 world = center + half_extent * (n + face_u[face] * corner.x + face_v[face] * corner.y);
    gl_Position = pc.view_projection * vec4(world, 1.0);
    out_position = world;
    out_material = int(in_center_material.w + 0.5);
    out_color = in_color_emissive;
    out_box_min = center - half_extent;
    out_box_max = center + half_extent;
    out_face_light = vec3(0.0);
    out_face_bounce = vec3(0.0);
    out_probe_light = vec3(0.0);
    if (out_material == 4) { // lit_probes: world_renderer.hpp ProbeRecord, at texel `emissive`
        const int base = int(in_color_emissive.w + 0.5);
        out_color.a = 0.0;
        if (face < 4) out_probe_light = probe_face_light(base, n);
    }
    out_texel = ivec4(0);
    if (TEXEL && out_material == 5) { // texel_lit: world_renderer.hpp TexelRecord, at texel `emissive`
        const int base = int(in_color_emissive.w + 0.5);
        const vec4 texture = texelFetch(u_boxes, base);
        const vec4 rect = texelFetch(u_boxes, base + 1 + face);
        const int size = int(texture.y + 0.5);
        out_texel = ivec4(int(texture.x + 0.5) + int(rect.y + 0.5) * size + int(rect.x + 0.5), size, int(rect.z + 0.5),
                          int(rect.w + 0.5));
        out_color.a = texture.w; // its glow
        // Its baked-light probe record (texture.z: 1 + the record's first texel; 0 none).
        if (face < 4 && texture.z > 0.5) out_probe_light = probe_face_light(int(texture.z + 0.5) - 1, n);
    }
    if (WALL_TOP_PER_FACE && HAS_GI) {
        set_gi_shading();
        out_face_light = surface_light(vec3(center.x, center.y + half_extent.y, center.z), vec3(0.0, 1.0, 0.0));
        if (BOUNCE_STYLED)
            out_face_bounce = surface_bounce(vec3(center.x, center.y + half_extent.y, center.z), vec3(0.0, 1.0, 0.0));
    }
}
