#version 450
// The game's world renderer, fragment stage: GI lighting through the shared shading library
// (shading.glsl, the twin of engine/gi/src/shading.cpp: ground / wall face / wall top
// routing), a subtle procedural pixel-art pattern, emission, the tone map, then the art
// controls (ordered dither, posterize, palette) in sRGB-encoded space. The target is sRGB:
// the shader writes linear colour and the attachment encodes it.
//
// Bindings, frame constants and specialisation: lantern/game_world.glsl.
#extension GL_GOOGLE_include_directive : require
#include "lantern/game_world.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) flat in int in_material;
layout(location = 2) flat in vec4 in_color;
layout(location = 3) flat in vec3 in_box_min;
layout(location = 4) flat in vec3 in_box_max;
layout(location = 5) flat in vec3 in_face_light; // WALL_TOP_PER_FACE: the top's light
layout(location = 6) flat in vec3 in_probe_light; // lit_probes: the baked light's direction
layout(location = 7) flat in ivec4 in_texel; // texel_lit: the face's first atlas texel, texture size, face width, height
layout(location = 8) flat in vec3 in_face_bounce; // WALL_TOP_PER_FACE: the bounce part of in_face_light

layout(location = 0) out vec4 out_color;

const int MATERIAL_GROUND = 0, MATERIAL_WALL = 1, MATERIAL_PROP = 2, MATERIAL_GLOW = 3, MATERIAL_LIT_PROBES = 4,
          MATERIAL_TEXEL_LIT = 5;

// The atlas texel of a texel_lit box's face under `pos` (texel::box_model's layout: a face's
// texel (i, j) counts i along its `right` and j down from its top edge, seen from outside).
int face_texel(vec3 pos) {
    const vec3 p = pos - in_box_min, e = max(in_box_max - in_box_min, vec3(1e-6));
    float s, t; // across the face along `right`, and up it, 0..1
    if (FACE == 0) { s = 1.0 - p.z / e.z; t = p.y / e.y; }
    else if (FACE == 1) { s = p.z / e.z; t = p.y / e.y; }
    else if (FACE == 2) { s = p.x / e.x; t = p.y / e.y; }
    else if (FACE == 3) { s = 1.0 - p.x / e.x; t = p.y / e.y; }
    else { s = p.x / e.x; t = 1.0 - p.z / e.z; }
    const int i = clamp(int(floor(s * float(in_texel.z))), 0, in_texel.z - 1);
    const int j = clamp(int(floor((1.0 - t) * float(in_texel.w))), 0, in_texel.w - 1);
    return in_texel.x + j * in_texel.y + i;
}

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

// ---- the HUD's GI views (GI_VIEW != 0)

const float TAU = 6.28318531;

// The view texture's texel under `pos` (seen from above); false when outside the window.
bool view_texel(vec3 pos, out vec4 v, out ivec2 t) {
    t = ivec2(floor((pos.xz - pc.window.xy) * pc.view_params.x));
    v = vec4(0.0);
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, pc.view_tex.xy))) return false;
    v = texelFetch(u_view, t.y * pc.view_tex.z + t.x);
    return true;
}

// Light views return light (tone-mapped by the caller); the others a display colour.
vec3 gi_view_color(vec3 pos) {
    vec4 v;
    ivec2 t;
    if (!view_texel(pos, v, t)) return vec3(0.03, 0.0, 0.05); // outside the GI window
    if (GI_VIEW == 1) return v.rgb;
    if (GI_VIEW == 2) { // distance in grid texels: blue near walls to warm far, a darker band
                        // every 2 texels, walls black
        float d = v.r;
        if (d <= 0.0) return vec3(0.0);
        vec3 c = mix(vec3(0.95, 0.65, 0.3), vec3(0.1, 0.2, 0.55), exp(-0.3 * d));
        return c * (fract(d * 0.5) < 0.15 ? 0.55 : 1.0);
    }
    if (GI_VIEW == 3) { // direction to the nearest wall: x as red, y (world z) as green
        if (v.r <= 0.0) return vec3(0.0);
        return vec3(0.5 + 0.5 * v.g, 0.5 + 0.5 * v.b, 0.5);
    }
    if (GI_VIEW == 5) { // the baked light's bricks by level (alpha: level + 1), shaded by the light
        const vec3 levels[4] = vec3[4](vec3(0.9, 0.2, 0.15), vec3(0.95, 0.85, 0.2), vec3(0.25, 0.8, 0.3), vec3(0.2, 0.45, 0.95));
        int level = int(v.a + 0.5) - 1;
        if (level < 0 || level > 3) return vec3(0.02);
        float shade = 0.55 + 0.45 * clamp(max(v.r, max(v.g, v.b)), 0.0, 1.0);
        return levels[level] * shade;
    }
    // GI_VIEW 4: the RGBA8 view of a 32-bit word, x | y << 16 of the nearest wall texel.
    uint word = packUnorm4x8(v);
    if (word == 0xFFFFFFFFu) return vec3(0.0); // no wall in reach
    ivec2 nearest = ivec2(int(word & 0xFFFFu), int(word >> 16));
    if (nearest == t) return vec3(1.0);        // a wall texel: its own seed
    uint h = hash3(ivec3(nearest, 7));
    return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) * (0.7 / 255.0) + 0.15;
}

// Seed 002's runtime knobs (BounceStyle in world_renderer.hpp; knobs: self, bleed): the
// bounce light `bounce` as a surface of albedo `albedo` reflects it.
vec3 reflected_bounce(vec3 bounce, vec3 albedo, vec2 knobs) {
    const vec3 chroma = albedo - (albedo.r + albedo.g + albedo.b) / 3.0;
    const float len = length(chroma);
    if (len > 1e-6) {
        const vec3 c = chroma / len;
        bounce -= (1.0 - knobs.x) * max(dot(bounce, c), 0.0) * c;
    }
    return bounce * mix(albedo, vec3(1.0), knobs.y);
}
// The knobs of a material's set: the world's for ground and walls, the characters' else.
vec2 bounce_knobs(int material) {
    return material == MATERIAL_GROUND || material == MATERIAL_WALL ? pc.bounce.xy : pc.bounce.zw;
}
// The defaults (self 1, bleed 0) take the plain path: albedo x light, as before the knobs.
bool bounce_styled(vec2 knobs) { return knobs.x != 1.0 || knobs.y != 0.0; }

void main() {
    if (XRAY) {
        // Every other pixel, in the box's own colour: the world behind still shows through.
        if (((int(gl_FragCoord.x) + int(gl_FragCoord.y)) & 1) != 0) discard;
        out_color = vec4(in_color.rgb, 1.0);
        return;
    }
    if (GI_VIEW != 0) {
        // Side faces sample just inside their box (their own tile), not the tile boundary.
        const vec3 normals[4] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 0, -1));
        vec3 pos = clamp(in_position, in_box_min, in_box_max);
        if (FACE < 4) pos -= normals[min(FACE, 3)] * 1e-3;
        vec3 c = gi_view_color(pos);
        if (GI_VIEW == 1) c = tone_map(c, int(pc.config.y), pc.config.z);
        out_color = vec4(c, 1.0);
        return;
    }
    set_gi_shading();
    vec3 color;
    if (in_material == MATERIAL_GLOW) {
        color = in_color.rgb * in_color.a;
    } else if (TEXEL && in_material == MATERIAL_TEXEL_LIT && in_texel.y > 0) {
        // Light, albedo and the GI's bounce all by the texel: the model's light changes in
        // steps of its art's texels.
        const int texel = face_texel(clamp(in_position, in_box_min, in_box_max));
        vec3 light = texel_lit[texel].rgb;
        const vec3 albedo = texel_albedo[texel].rgb * in_color.rgb;
        const vec2 knobs = bounce_knobs(MATERIAL_TEXEL_LIT);
        // The GI's bounce at the texel, and the baked light's direction on a side face: read
        // once for both branches (lavapipe runs both).
        const vec3 bounce = HAS_GI ? ground_indirect_light(texel_surfaces[3 * texel].xyz) + in_probe_light : vec3(0.0);
        if (HAS_GI && BOUNCE_STYLED && bounce_styled(knobs)) {
            color = max(albedo * light + reflected_bounce(bounce, albedo, knobs), vec3(0.0)) + albedo * in_color.a;
        } else {
            if (HAS_GI) light = max(light + bounce, vec3(0.0));
            color = albedo * (light + in_color.a); // a: its glow (a crystal)
        }
    } else {
        // Interpolation can step a hair off the box at its edges: keep the point on it, so
        // the routing (which cell, which side) follows the face being drawn.
        const vec3 pos = clamp(in_position, in_box_min, in_box_max);
        vec3 albedo = in_color.rgb;
        if (pc.art.w != 0) albedo *= pattern(in_material, FACE, pos);
        const vec3 normals[5] = vec3[](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, 1, 0));
        const vec2 knobs = bounce_knobs(in_material);
        // The light, read once for both branches (lavapipe runs both).
        vec3 light = vec3(0.0);
        if (HAS_GI) light = WALL_TOP_PER_FACE ? in_face_light : surface_light(pos, normals[FACE]);
        if (HAS_GI && BOUNCE_STYLED && bounce_styled(knobs)) {
            // The light split into its direct part and its bounce, which the knobs reshape.
            const vec3 gi_bounce = WALL_TOP_PER_FACE ? in_face_bounce : surface_bounce(pos, normals[FACE]);
            const vec3 direct = light - gi_bounce;
            const vec3 bounce = in_material == MATERIAL_LIT_PROBES ? gi_bounce + in_probe_light : gi_bounce;
            color = max(albedo * direct + reflected_bounce(bounce, albedo, knobs), vec3(0.0)) + in_color.rgb * in_color.a;
        } else {
            if (HAS_GI && in_material == MATERIAL_LIT_PROBES) light = max(light + in_probe_light, vec3(0.0));
            color = albedo * light + in_color.rgb * in_color.a;
        }
    }
    color = tone_map(color, int(pc.config.y), pc.config.z);
    out_color = vec4(apply_art(color), 1.0);
}
