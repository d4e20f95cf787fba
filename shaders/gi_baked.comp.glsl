// The baked light read from the bake's brick atlas (docs/baked.md, "At run time"): each
// window texel reads seed 002's atlas (the indirection texel of its cell, nearest, then one
// bilinear read of the RGBM atlas inside the brick): open ground into baked_ground (layer 0),
// the texels of a wall tile whose face f is exposed into baked_face_f (layer 1 + f, alpha 1
// at wall texels, as wall_indirect writes), and the HUD's view. The baked pass adds them to
// the frame's textures (gi_add.comp). A pulsing part (layers 5..9) goes into textures of its
// own (baked_pulse_*, at pulse 1), which the baked pass adds scaled by each frame's pulse, so
// a new pulse reads no atlas. A keyed moving sun adds its colour x the two sun keys around its
// time of day, blended (baked_light.hpp BakedSun). C++ reference:
// engine/gi/src/rows/baked.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require

struct BakedParams {
    int origin_x, origin_z; // world tile of the baked grid's texel (0, 0)
    int resolution;         // baked grid texels per tile
    int width, height;      // baked grid texels
    int parts;              // bit 0: layers 5..9 hold the pulsing glow's light (seed 004's pulsing
                            // emission), written apart (FEATURES & 1); bits 1..: the moving
                            // sun's first key layer + 1 (0: none; FEATURES & 2 when not 0)
    float intensity;        // gi.baked_intensity
    int offset;             // the dispatch's first texel, x | y << 16 (a scrolled window's new strips)
};
#define GI_PASS_PARAMS BakedParams
#include "lantern/gi_common.glsl"

// The parts the atlas holds, as specialisation constants: lavapipe runs an untaken branch's
// body too, masked, so a branch on `parts` would pay for the pulsing and keyed reads in every
// frame (docs/performance.md, "The baked sampling's untaken reads").
const bool PULSING = (FEATURES & 1u) != 0u;  // parts bit 0: layers 5..9 hold the pulsing glow's light
const bool SUN_KEYS = (FEATURES & 2u) != 0u; // parts >> 1 is a keyed moving sun's first layer + 1

layout(binding = 0) uniform usamplerBuffer u_walls;
layout(std140, binding = 1) uniform ProxyBlock { GpuShadowProxy proxies[1]; } u_proxies; // unused
layout(binding = 2) uniform sampler2D u_atlas;         // RGBA8 RGBM, linear filtering
layout(binding = 3) uniform usampler2D u_indirection;  // RGBA8_UINT, read with texelFetch
layout(std430, binding = 4) writeonly buffer Ground { uvec2 texels[]; } o_ground;
layout(std430, binding = 5) writeonly buffer FacePX { uvec2 texels[]; } o_face_px;
layout(std430, binding = 6) writeonly buffer FaceNX { uvec2 texels[]; } o_face_nx;
layout(std430, binding = 7) writeonly buffer FacePZ { uvec2 texels[]; } o_face_pz;
layout(std430, binding = 8) writeonly buffer FaceNZ { uvec2 texels[]; } o_face_nz;
layout(std430, binding = 9) writeonly buffer View { uvec2 texels[]; } o_view; // the HUD's: rgb baked, a level + 1
layout(binding = 10) uniform samplerBuffer u_sun; // the sun keys' weights: colour x (1 - blend), colour x blend
// The pulsing part at pulse 1 (parts bit 0): the ground's, then each face's.
layout(std430, binding = 11) writeonly buffer PulseGround { uvec2 texels[]; } o_pulse_ground;
layout(std430, binding = 12) writeonly buffer PulsePX { uvec2 texels[]; } o_pulse_px;
layout(std430, binding = 13) writeonly buffer PulseNX { uvec2 texels[]; } o_pulse_nx;
layout(std430, binding = 14) writeonly buffer PulsePZ { uvec2 texels[]; } o_pulse_pz;
layout(std430, binding = 15) writeonly buffer PulseNZ { uvec2 texels[]; } o_pulse_nz;

#include "lantern/gi_shadow.glsl"

const int LAYERS = 5;
const float RGBM_RANGE = 8.0;

// The baked light of `layer` at world point p: gi::sample_bricks, with the hardware's
// bilinear filter; `level` the brick's level + 1 (0: none).
vec3 baked_sample(int layer, vec2 p, out float level) {
    level = 0.0;
    vec2 g = (p - vec2(pc.pass.origin_x, pc.pass.origin_z)) * float(pc.pass.resolution);
    if (!(g.x >= 0.0 && g.y >= 0.0 && g.x < float(pc.pass.width) && g.y < float(pc.pass.height))) return vec3(0.0);
    ivec2 cells = (ivec2(pc.pass.width, pc.pass.height) + 3) / 4; // layer k's rows: k x cells.y .. (the image may be larger)
    ivec2 cell = clamp(ivec2(floor(g / 4.0)), ivec2(0), cells - 1);
    uvec4 ind = texelFetch(u_indirection, ivec2(cell.x, cell.y + layer * cells.y), 0);
    if (ind.a == 0u) return vec3(0.0);
    level = float(ind.a);
    float s = float(1 << (int(ind.a) - 1)), side = 4.0 * s;
    ivec2 brick = ivec2(int(ind.r) | (int(ind.b & 15u) << 8), int(ind.g) | (int(ind.b >> 4u) << 8));
    vec2 o = floor(g / side) * side;
    // The brick's texel coordinate: probe k's centre at k + 1.5 (the apron is texel 0).
    vec2 t = vec2(brick * 6) + (g - o) / s + 1.0;
    vec4 v = texture(u_atlas, t / vec2(textureSize(u_atlas, 0)));
    return v.rgb * v.a * RGBM_RANGE;
}

// The steady light the frame takes from `layer` (BakedLight::light at pulse 0), times
// gi.baked_intensity; `level` the layer's brick level + 1.
vec3 baked_light(int layer, vec2 p, out float level) {
    vec3 v = baked_sample(layer, p, level);
    int sun_layer = (pc.pass.parts >> 1) - 1;
    if (SUN_KEYS && sun_layer >= 0) {
        float key_level;
        vec3 below = baked_sample(sun_layer + layer, p, key_level);
        vec3 above = baked_sample(sun_layer + LAYERS + layer, p, key_level);
        v += texelFetch(u_sun, 0).rgb * below + texelFetch(u_sun, 1).rgb * above;
    }
    return v * pc.pass.intensity;
}

void main() {
    ivec2 o = block_origin() + ivec2(pc.pass.offset & 0xFFFF, pc.pass.offset >> 16);
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x >= pc.size.x) continue;
            int index = texel_index(x, y);
            vec2 p = texel_center(x, y);
            ivec2 cell = ivec2(floor(p));
            bool wall = is_wall(cell);
            // The layers this texel takes, bit 0 the ground's and bit 1 + f face f's: one loop
            // over them rather than a branch per layer, since lavapipe runs a branch for every
            // lane when one lane takes it, and neighbouring lanes mix ground and walls.
            uint layers = 1u;
            if (wall) {
                vec4 mask = FACES != 0u ? wall_face_mask(cell) * face_bits_mask(FACES) : vec4(0.0);
                layers = (mask.x > 0.0 ? 2u : 0u) | (mask.y > 0.0 ? 4u : 0u) | (mask.z > 0.0 ? 8u : 0u) |
                         (mask.w > 0.0 ? 16u : 0u);
            }
            vec3 ground = vec3(0.0), v0 = vec3(0.0), v1 = vec3(0.0), v2 = vec3(0.0), v3 = vec3(0.0);
            vec3 pg = vec3(0.0), p0 = vec3(0.0), p1 = vec3(0.0), p2 = vec3(0.0), p3 = vec3(0.0); // pulsing part
            vec4 shown = vec4(0.0); // the HUD's: the light at pulse 1, and the first layer's level + 1
            for (uint m = layers; m != 0u; m &= m - 1u) {
                int layer = findLSB(m);
                float level;
                vec3 c = baked_light(layer, p, level);
                vec3 q = vec3(0.0);
                if (PULSING) {
                    float pulse_level;
                    q = baked_sample(LAYERS + layer, p, pulse_level) * pc.pass.intensity;
                }
                if (layer == 0) { ground = c; pg = q; }
                else if (layer == 1) { v0 = c; p0 = q; }
                else if (layer == 2) { v1 = c; p1 = q; }
                else if (layer == 3) { v2 = c; p2 = q; }
                else { v3 = c; p3 = q; }
                shown.rgb += c + q;
                if (shown.a == 0.0) shown.a = level;
            }
            o_ground.texels[index] = pack_rgba16f(vec4(ground, 0.0));
            o_view.texels[index] = pack_rgba16f(shown);
            float alpha = wall ? 1.0 : 0.0; // as wall_indirect writes it
            if (computes_face(FACES, 0)) o_face_px.texels[index] = pack_rgba16f(vec4(v0, alpha));
            if (computes_face(FACES, 1)) o_face_nx.texels[index] = pack_rgba16f(vec4(v1, alpha));
            if (computes_face(FACES, 2)) o_face_pz.texels[index] = pack_rgba16f(vec4(v2, alpha));
            if (computes_face(FACES, 3)) o_face_nz.texels[index] = pack_rgba16f(vec4(v3, alpha));
            if (PULSING) {
                o_pulse_ground.texels[index] = pack_rgba16f(vec4(pg, 0.0));
                if (computes_face(FACES, 0)) o_pulse_px.texels[index] = pack_rgba16f(vec4(p0, alpha));
                if (computes_face(FACES, 1)) o_pulse_nx.texels[index] = pack_rgba16f(vec4(p1, alpha));
                if (computes_face(FACES, 2)) o_pulse_pz.texels[index] = pack_rgba16f(vec4(p2, alpha));
                if (computes_face(FACES, 3)) o_pulse_nz.texels[index] = pack_rgba16f(vec4(p3, alpha));
            }
        }
    }
}
