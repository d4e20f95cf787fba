#version 450
// The game's world renderer, fragment stage: GI lighting through the shared shading library
// (shading.glsl, the twin of engine/gi/src/shading.cpp: ground / wall face / wall top
// routing), a subtle procedural pixel-art pattern, emission, the tone map, then the art
// controls (ordered dither, posterize, palette) in sRGB-encoded space. The target is sRGB:
// the shader writes linear colour and the attachment encodes it.
//
// Frame constants: the uniform block `pc` (gi_walls.glsl reads pc.grid and pc.grid_phase;
// mirrored by WorldFrame in game/src/world_renderer.cpp). GI textures: uniform texel buffers,
// texel (x, y) at y * pitch + x (gi_common.glsl texel_index); absent ones are bound to a small
// dummy buffer and flagged absent in pc.gi.y.
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_types.glsl"

// Specialisation (lavapipe executes both sides of every branch, so what is not compiled out
// costs every pixel): the face drawn (its normal is a constant, and the routing folds), GI
// on or off, art controls on or off.
layout(constant_id = 0) const int FACE = 4; // 0 +x, 1 -x, 2 +z, 3 -z, 4 top
layout(constant_id = 1) const bool HAS_GI = true;
layout(constant_id = 2) const bool HAS_ART = false;
// What the wall lookup answers for this draw's geometry: 0 the wall grid; 1 open ground
// (ground boxes: only their open tiles are ever seen, walls stand on the others); 2 wall
// (the sides of wall boxes: they are on wall tiles). With 1 or 2 the routing folds at
// compile time to the branch it would take for every visible pixel.
layout(constant_id = 3) const int WALL_LOOKUP = 0;

layout(std140, set = 0, binding = 0) uniform WorldFrame {
    vec4 window;       // gi_shading.window: min x, min z (world), width, height (texels)
    vec4 config;       // gi_shading.config: resolution, tone map, white point, angle scale
    ivec4 grid;        // wall grid width, height, origin x, origin z
    ivec4 grid_phase;  // toroidal phase (x, z), 0, 0
    ivec4 gi;          // x: texel pitch, y: presence bits (bit GI_*), z: sun count, w: 1 = GI (HAS_GI)
    ivec4 art;         // x: posterize levels (0 off), y: dither, z: palette colours (0 off), w: pattern
                       // (x, y, z all 0: HAS_ART is false)
    vec4 art_params;   // x: dither amplitude (encoded units)
    vec4 palette[16];  // sRGB-encoded palette colours
    GpuDirectionalLight suns[8];
} pc;

layout(set = 0, binding = 1) uniform usamplerBuffer u_walls;
layout(set = 0, binding = 2) uniform samplerBuffer u_direct;
layout(set = 0, binding = 3) uniform samplerBuffer u_indirect;
layout(set = 0, binding = 4) uniform samplerBuffer u_ao;
layout(set = 0, binding = 5) uniform samplerBuffer u_shadow;
layout(set = 0, binding = 6) uniform samplerBuffer u_wall_direct_px;
layout(set = 0, binding = 7) uniform samplerBuffer u_wall_direct_nx;
layout(set = 0, binding = 8) uniform samplerBuffer u_wall_direct_pz;
layout(set = 0, binding = 9) uniform samplerBuffer u_wall_direct_nz;
layout(set = 0, binding = 10) uniform samplerBuffer u_wall_indirect_px;
layout(set = 0, binding = 11) uniform samplerBuffer u_wall_indirect_nx;
layout(set = 0, binding = 12) uniform samplerBuffer u_wall_indirect_pz;
layout(set = 0, binding = 13) uniform samplerBuffer u_wall_indirect_nz;

#include "lantern/gi_walls.glsl"
#include "lantern/shading.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) flat in int in_material;
layout(location = 2) flat in vec4 in_color;
layout(location = 3) flat in vec3 in_box_min;
layout(location = 4) flat in vec3 in_box_max;

layout(location = 0) out vec4 out_color;

const int MATERIAL_GROUND = 0, MATERIAL_WALL = 1, MATERIAL_PROP = 2, MATERIAL_GLOW = 3;

// ---- the shading library's inputs

bool gi_has(int t) { return ((uint(pc.gi.y) >> uint(t)) & 1u) != 0u; }
vec4 gi_fetch(int t, ivec2 texel) {
    int index = texel.y * pc.gi.x + texel.x;
    if (t == GI_DIRECT) return texelFetch(u_direct, index);
    if (t == GI_INDIRECT) return texelFetch(u_indirect, index);
    if (t == GI_AO) return texelFetch(u_ao, index);
    if (t == GI_SHADOW) return texelFetch(u_shadow, index);
    if (t == GI_WALL_DIRECT + 0) return texelFetch(u_wall_direct_px, index);
    if (t == GI_WALL_DIRECT + 1) return texelFetch(u_wall_direct_nx, index);
    if (t == GI_WALL_DIRECT + 2) return texelFetch(u_wall_direct_pz, index);
    if (t == GI_WALL_DIRECT + 3) return texelFetch(u_wall_direct_nz, index);
    if (t == GI_WALL_INDIRECT + 0) return texelFetch(u_wall_indirect_px, index);
    if (t == GI_WALL_INDIRECT + 1) return texelFetch(u_wall_indirect_nx, index);
    if (t == GI_WALL_INDIRECT + 2) return texelFetch(u_wall_indirect_pz, index);
    return texelFetch(u_wall_indirect_nz, index);
}
bool gi_wall_tile(ivec2 tile) { return WALL_LOOKUP == 1 ? false : WALL_LOOKUP == 2 ? true : is_wall(tile); }
int gi_sun_count() { return pc.gi.z; }
GpuDirectionalLight gi_sun(int i) { return pc.suns[i]; }

// ---- the pixel-art pattern: 8 texels per tile on every face, a function of world position

const float PATTERN_TEXELS = 8.0;

uint hash3(ivec3 p) { // integer hash (lowbias32-style mixing of three coordinates)
    uint h = uint(p.x) * 0x8da6b343u ^ uint(p.y) * 0xd8163841u ^ uint(p.z) * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}
float hash01(ivec3 p) { return float(hash3(p) >> 8) * (1.0 / 16777216.0); }

// Brightness factor of the albedo around 1: per-texel variation, speckle on the ground,
// staggered bricks with darker mortar on wall faces, slabs with darker seams on wall tops.
float pattern(int material, int face, vec3 pos) {
    // Texel coordinates on the face's plane (tops: x, z; x faces: z, y; z faces: x, y).
    vec2 uv = face == 4 ? pos.xz : (face < 2 ? pos.zy : pos.xy);
    ivec2 t = ivec2(floor(uv * PATTERN_TEXELS));
    float n = hash01(ivec3(t, face * 8 + material));
    if (material == MATERIAL_GROUND) {
        float v = 1.0 + (n - 0.5) * 0.10;
        float speck = hash01(ivec3(t, 97));
        if (speck > 0.94) v *= 0.80;        // dark pebbles
        else if (speck < 0.025) v *= 1.12;  // bright grit
        return v;
    }
    if (material == MATERIAL_WALL) {
        if (face == 4) { // slab top: seams along the tile edges
            bool seam = (t.x & 7) == 0 || (t.y & 7) == 0;
            return (1.0 + (n - 0.5) * 0.08) * (seam ? 0.84 : 1.0);
        }
        // Bricks 8 texels wide and 4 high (one mortar row and column), rows offset by half.
        int row = t.y >> 2;
        int bx = t.x + ((row & 1) << 2);
        bool mortar = (t.y & 3) == 0 || (bx & 7) == 0;
        if (mortar) return 0.78 + n * 0.04;
        float brick = hash01(ivec3(bx >> 3, row, 53 + face));
        return (1.0 + (brick - 0.5) * 0.14) * (1.0 + (n - 0.5) * 0.06);
    }
    return 1.0 + (n - 0.5) * 0.10; // props
}

// ---- art controls (sRGB-encoded space)

vec3 srgb_encode(vec3 c) { return vec3(linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b)); }
float srgb_decode1(float v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }
vec3 srgb_decode(vec3 s) { return vec3(srgb_decode1(s.r), srgb_decode1(s.g), srgb_decode1(s.b)); }

const float bayer4[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

vec3 apply_art(vec3 c) {
    if (!HAS_ART) return c;
    vec3 s = srgb_encode(c);
    if (pc.art.y != 0) {
        ivec2 p = ivec2(gl_FragCoord.xy) & 3;
        float threshold = (bayer4[p.y * 4 + p.x] + 0.5) / 16.0 - 0.5; // -15/32 .. 15/32
        s = clamp(s + threshold * pc.art_params.x, 0.0, 1.0);
    }
    if (pc.art.x != 0) {
        float steps = float(pc.art.x - 1);
        s = floor(s * steps + 0.5) / steps;
    }
    if (pc.art.z != 0) {
        vec3 best = pc.palette[0].rgb;
        float best_d = 1e30;
        for (int i = 0; i < pc.art.z; ++i) {
            vec3 d = s - pc.palette[i].rgb;
            float dist = dot(d * d, vec3(2.0, 4.0, 3.0));
            if (dist < best_d) {
                best_d = dist;
                best = pc.palette[i].rgb;
            }
        }
        s = best;
    }
    return srgb_decode(s);
}

void main() {
    gi_shading.window = pc.window;
    gi_shading.config = pc.config;
    vec3 color;
    if (in_material == MATERIAL_GLOW) {
        color = in_color.rgb * in_color.a;
    } else {
        // Interpolation can step a hair off the box at its edges: keep the point on it, so
        // the routing (which cell, which side) follows the face being drawn.
        const vec3 pos = clamp(in_position, in_box_min, in_box_max);
        vec3 albedo = in_color.rgb;
        if (pc.art.w != 0) albedo *= pattern(in_material, FACE, pos);
        vec3 light = vec3(0.0);
        if (HAS_GI) {
            const vec3 normals[5] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, 1, 0));
            light = surface_light(pos, normals[FACE]);
        }
        color = albedo * light + in_color.rgb * in_color.a;
    }
    color = tone_map(color, int(pc.config.y), pc.config.z);
    out_color = vec4(apply_art(color), 1.0);
}
