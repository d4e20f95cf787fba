// The shading library: how a surface samples the GI textures. GLSL twin of
// engine/gi/src/shading.cpp (keep them in step); docs/gi.md describes the routing.
//
// Requires gi_types.glsl. The includer defines the functions declared below (after the
// include) and fills the global `gi_shading` before shading.
#ifndef LANTERN_SHADING_GLSL
#define LANTERN_SHADING_GLSL

const int GI_DIRECT = 0;
const int GI_INDIRECT = 1;
const int GI_AO = 2;
const int GI_SHADOW = 3;
const int GI_WALL_DIRECT = 4;   // + face (0 +X, 1 -X, 2 +Z, 3 -Z)
const int GI_WALL_INDIRECT = 8; // + face
const int GI_WALL_UPPER = 12;   // + face: unfolded proxy shadows (rgb: light at the top, a: edge height)

const int TONE_NONE = 0, TONE_REINHARD = 1, TONE_REINHARD_WHITE = 2, TONE_ACES = 3;
const int SURFACE_GROUND = 0, SURFACE_WALL_FACE = 1, SURFACE_WALL_TOP = 2;

struct GiShadingParams {
    vec4 window;   // min_x, min_z, width (texels), height (texels)
    vec4 config;   // resolution, tone map, white point, directional angle scale
    vec4 options;  // x: gi.wall_lighting (1/0), y: gi.ao.walls (1/0), z, w: 0
};
GiShadingParams gi_shading;

vec4 gi_fetch(int texture_id, ivec2 texel); // GI_DIRECT ... GI_WALL_INDIRECT + face
bool gi_has(int texture_id);                // false: treat as zero (AO absent: no AO)
bool gi_wall_tile(ivec2 tile);              // the wall grid; out of bounds is air
int gi_sun_count();
GpuDirectionalLight gi_sun(int i);

float gi_saturate(float x) { return clamp(x, 0.0, 1.0); }

ivec2 gi_texel_at(vec2 p) {
    float res = gi_shading.config.x;
    return ivec2(clamp(int(floor((p.x - gi_shading.window.x) * res)), 0, int(gi_shading.window.z) - 1),
                 clamp(int(floor((p.y - gi_shading.window.y) * res)), 0, int(gi_shading.window.w) - 1));
}
vec3 gi_fetch_rgb(int t, ivec2 texel) { return gi_has(t) ? gi_fetch(t, texel).rgb : vec3(0.0); }
bool gi_wall_at(vec2 p) { return gi_wall_tile(ivec2(floor(p))); }

vec3 tone_map(vec3 c, int mode, float white_point) {
    c = max(c, vec3(0.0));
    if (mode == TONE_REINHARD) return c / (1.0 + c);
    if (mode == TONE_REINHARD_WHITE) return c * (1.0 + c / (white_point * white_point)) / (1.0 + c);
    if (mode == TONE_ACES) return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    return c;
}

int dominant_face(vec3 n) {
    if (abs(n.x) >= abs(n.z)) return n.x >= 0.0 ? 0 : 1;
    return n.z >= 0.0 ? 2 : 3;
}

// Half a GI texel into the wall, where the face's light is stored.
vec2 wall_sample_position(vec3 pos, vec3 n) { return pos.xz - n.xz * (0.5 / gi_shading.config.x); }

int classify_surface(vec3 pos, vec3 n) {
    if (gi_shading.options.x == 0.0) return SURFACE_GROUND; // wall lighting off: walls are ground
    float nxz = sqrt(n.x * n.x + n.z * n.z);
    if (nxz >= 0.5) {
        if (gi_wall_at(wall_sample_position(pos, n)) || gi_wall_at(pos.xz)) return SURFACE_WALL_FACE;
    } else if (n.y >= 0.5 && nxz <= 0.35) {
        if (gi_wall_at(floor(pos.xz) + 0.5)) return SURFACE_WALL_TOP;
    }
    return SURFACE_GROUND;
}

// AO on a wall face (gi.ao.walls): the ground texel just outside the face, at the same
// place along it. `inside` is wall_sample_position, in the wall tile.
vec2 face_ao_position(vec2 inside, vec2 p, int face) {
    vec2 cell = floor(inside);
    float h = 0.5 / gi_shading.config.x;
    if (face == 0) return vec2(cell.x + 1.0 + h, p.y);
    if (face == 1) return vec2(cell.x - h, p.y);
    if (face == 2) return vec2(p.x, cell.y + 1.0 + h);
    return vec2(p.x, cell.y - h);
}

float gi_sun_angle(GpuDirectionalLight sun) {
    return mix(gi_saturate(-sun.direction_base.y * 2.0), 1.0, gi_shading.config.w);
}

vec3 ground_indirect_average(vec2 p) {
    vec2 cell_center = floor(p) + 0.5;
    vec3 sum = vec3(0.0);
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dx = -1; dx <= 1; ++dx) {
            vec2 q = cell_center + vec2(float(dx), float(dz));
            if (gi_wall_at(q)) continue;
            sum += gi_fetch_rgb(GI_INDIRECT, gi_texel_at(q));
            ++n;
        }
    return n > 0 ? sum / float(n) : vec3(0.0);
}

// Linear light arriving at the surface (before tone mapping).
vec3 surface_light(vec3 pos, vec3 n) {
    int kind = classify_surface(pos, n);
    if (kind == SURFACE_WALL_FACE) {
        vec2 inside = wall_sample_position(pos, n);
        ivec2 t = gi_texel_at(inside);
        int face = dominant_face(n);
        vec3 direct = gi_fetch_rgb(GI_WALL_DIRECT + face, t);
        if (gi_has(GI_WALL_UPPER + face)) { // above the proxies' shadow edge: the light at the top
            vec4 upper = gi_fetch(GI_WALL_UPPER + face, t);
            if (pos.y >= upper.a) direct = upper.rgb;
        }
        vec3 light = direct + gi_fetch_rgb(GI_WALL_INDIRECT + face, t);
        if (gi_shading.options.y != 0.0 && gi_has(GI_AO))
            light *= gi_fetch(GI_AO, gi_texel_at(face_ao_position(inside, pos.xz, face))).r;
        return light;
    }
    if (kind == SURFACE_WALL_TOP) {
        vec3 direct = vec3(0.0);
        if (gi_sun_count() > 0) {
            GpuDirectionalLight sun = gi_sun(0);
            direct = sun.color_multiplier.rgb * gi_sun_angle(sun);
        }
        return direct + ground_indirect_average(pos.xz);
    }
    ivec2 t = gi_texel_at(pos.xz);
    vec3 indirect = gi_fetch_rgb(GI_INDIRECT, t);
    float sun_visibility = gi_has(GI_SHADOW) ? gi_fetch(GI_SHADOW, t).g : 0.0;
    for (int i = 0; i < gi_sun_count(); ++i) {
        GpuDirectionalLight sun = gi_sun(i);
        indirect += sun.color_multiplier.rgb * gi_sun_angle(sun) * sun.bounce.x * (1.0 - sun_visibility);
    }
    vec3 combined = gi_fetch_rgb(GI_DIRECT, t) + indirect;
    if (gi_has(GI_AO)) combined *= gi_fetch(GI_AO, t).r;
    combined *= gi_wall_at(pos.xz) ? 0.0 : 1.0;
    return combined;
}

// The ground route's indirect light alone (surface_light without GI_DIRECT): the GI's bounce
// light at a point in the open, which per-texel lit models add to their own direct light
// (docs/texel.md). Only the game's raster draws such models; the lit image has none, so the
// C++ twin has no counterpart.
vec3 ground_indirect_light(vec3 pos) {
    ivec2 t = gi_texel_at(pos.xz);
    vec3 indirect = gi_fetch_rgb(GI_INDIRECT, t);
    float sun_visibility = gi_has(GI_SHADOW) ? gi_fetch(GI_SHADOW, t).g : 0.0;
    for (int i = 0; i < gi_sun_count(); ++i) {
        GpuDirectionalLight sun = gi_sun(i);
        indirect += sun.color_multiplier.rgb * gi_sun_angle(sun) * sun.bounce.x * (1.0 - sun_visibility);
    }
    if (gi_has(GI_AO)) indirect *= gi_fetch(GI_AO, t).r;
    return gi_wall_at(pos.xz) ? vec3(0.0) : indirect;
}

// The bounce part of surface_light (its GI_INDIRECT and wall_indirect terms, with AO as it
// applies them; the rest is direct light): what seed 002's runtime knobs act on in the
// game's raster (reflected_bounce in game_world.frag). Game-only, as ground_indirect_light.
vec3 surface_bounce(vec3 pos, vec3 n) {
    int kind = classify_surface(pos, n);
    if (kind == SURFACE_WALL_FACE) {
        vec2 inside = wall_sample_position(pos, n);
        vec3 light = gi_fetch_rgb(GI_WALL_INDIRECT + dominant_face(n), gi_texel_at(inside));
        if (gi_shading.options.y != 0.0 && gi_has(GI_AO))
            light *= gi_fetch(GI_AO, gi_texel_at(face_ao_position(inside, pos.xz, dominant_face(n)))).r;
        return light;
    }
    if (kind == SURFACE_WALL_TOP) return ground_indirect_average(pos.xz);
    return ground_indirect_light(pos);
}

vec3 shade(vec3 pos, vec3 n) {
    return tone_map(surface_light(pos, n), int(gi_shading.config.y), gi_shading.config.z);
}

float linear_to_srgb(float v) {
    v = gi_saturate(v);
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

#endif
