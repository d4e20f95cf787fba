// The game world shaders' shared inputs (game_world.vert.glsl and game_world.frag.glsl): the
// specialisation constants, the frame constants `pc` (mirrored by WorldFrame in
// game/src/world_renderer.cpp), the GI texel buffers, and the functions the shading library
// (shading.glsl, the twin of engine/gi/src/shading.cpp) asks its includer for. GI textures:
// uniform texel buffers, texel (x, y) at y * pitch + x (gi_common.glsl texel_index); absent
// ones are bound to a small dummy buffer and flagged absent in pc.gi.y.
#ifndef LANTERN_GAME_WORLD_GLSL
#define LANTERN_GAME_WORLD_GLSL
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
// (the sides and tops of wall boxes: they are on wall tiles). With 1 or 2 the routing folds at
// compile time to the branch it would take for every visible pixel.
layout(constant_id = 3) const int WALL_LOOKUP = 0;
// The HUD's GI views (WorldView::gi_view): 0 the lit scene; else every surface shows the
// texture u_view under it, seen from above: 1 light (tone-mapped), 2 distance field, 3
// direction map, 4 jump flood (packed nearest-wall coordinates).
layout(constant_id = 4) const int GI_VIEW = 0;
// The x-ray pass (DrawList::xray): a box's faces drawn only where something nearer hides them
// (depth test GREATER, no depth write), as a flat checkerboard of their colour, so the player
// stays visible behind walls.
layout(constant_id = 5) const bool XRAY = false;
// The texel_lit boxes' draws (Material texel_lit, docs/texel.md): their faces take the light of
// the per-texel passes at the texel under the pixel (bindings 20..22).
layout(constant_id = 6) const bool TEXEL = false;
// Seed 002's bounce knobs (pc.bounce) away from their defaults for the world or for characters.
// Their branch reads the GI a second time (surface_bounce), and on lavapipe a branch not
// taken still costs every pixel: with the knobs at their defaults (self 1, bleed 0) it doubled
// the ground's cost (lantern-bench-world, "ground only": 15.6 ms against 8 without it), so the
// renderer picks pipelines with it compiled in only while a knob is moved.
layout(constant_id = 7) const bool BOUNCE_STYLED = false;

// The frame constants (WorldFrame in game/src/world_renderer.cpp), read as frames[slot] with
// `slot` a push constant that is always 0. Why the indirection: lavapipe specialises a shader
// for the values of the uniform words its branches read when it can see their offsets
// ("uniform inlining", lvp_inline_uniforms.c) and keeps every variant until the pipeline is
// destroyed. The window origin, grid phase and camera change as the player walks, so a plain
// block compiled two shader variants a frame and grew the game by ~0.6 MB a frame. An offset
// that depends on a loaded value is out of inlining's reach, yet still uniform, so llvmpipe
// keeps its one-scalar-load path (a storage buffer costs a per-lane loop: the ground pass
// measured 3x slower). docs/performance.md, "Soak".
struct WorldFrame {
    mat4 view_projection; // WorldRenderer::view_projection (Vulkan clip space)
    vec4 camera;       // xyz camera position
    vec4 window;       // gi_shading.window: min x, min z (world), width, height (texels)
    vec4 config;       // gi_shading.config: resolution, tone map, white point, angle scale
    vec4 options;      // gi_shading.options: wall lighting, AO on walls (1/0)
    ivec4 grid;        // wall grid width, height, origin x, origin z
    ivec4 grid_phase;  // toroidal phase (x, z), 0, 0
    ivec4 gi;          // x: texel pitch, y: presence bits (bit GI_*), z: sun count, w: 1 = GI (HAS_GI)
    ivec4 art;         // x: posterize levels (0 off), y: dither, z: palette colours (0 off), w: pattern
                       // (x, y, z all 0: HAS_ART is false)
    vec4 art_params;   // x: dither amplitude (encoded units)
    vec4 bounce;       // seed 002's runtime knobs (BounceStyle): world self, bleed; characters self, bleed
    ivec4 view_tex;    // GI_VIEW's texture: width, height, pitch, 0
    vec4 view_params;  // x: its texels per world unit (from the window's min corner)
    ivec4 probes;      // the GI's live probes (u_probes): first tile x, z; count x | count z << 16; pitch (0: none)
    vec4 palette[16];  // sRGB-encoded palette colours
    GpuDirectionalLight suns[8];
};
layout(std140, set = 0, binding = 0) uniform WorldFrames {
    WorldFrame frames[2]; // two, so that no compiler may fold the index to 0
} u_frames;
layout(push_constant) uniform WorldSlot {
    int slot; // always 0
} u_slot;
#define pc (u_frames.frames[u_slot.slot])

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
layout(set = 0, binding = 14) uniform samplerBuffer u_wall_upper_px;
layout(set = 0, binding = 15) uniform samplerBuffer u_wall_upper_nx;
layout(set = 0, binding = 16) uniform samplerBuffer u_wall_upper_pz;
layout(set = 0, binding = 17) uniform samplerBuffer u_wall_upper_nz;
// binding 18: the boxes (game_world.vert.glsl)
layout(set = 0, binding = 19) uniform samplerBuffer u_view; // GI_VIEW's texture (RGBA16F or RGBA8 words)
// The per-texel light (texel::vk::TexelPasses): lit() and surfaces() (three vec4 per texel:
// the world position first), and each atlas texel's albedo. Dummies unless TEXEL draws run.
layout(std430, set = 0, binding = 20) readonly buffer TexelLit { vec4 texel_lit[]; };
layout(std430, set = 0, binding = 21) readonly buffer TexelSurfaces { vec4 texel_surfaces[]; };
layout(std430, set = 0, binding = 22) readonly buffer TexelAlbedo { vec4 texel_albedo[]; };
// The GI's live light probes (lantern/gi/probes.hpp): five RGBA16F texels a probe (a0, a1, b1,
// a2, b2; a0's alpha 1 in open ground), probe (i, j) at tile pc.probes.xy + 2 (i, j).
layout(set = 0, binding = 23) uniform samplerBuffer u_probes;

#include "lantern/gi_walls.glsl"
#include "lantern/shading.glsl"
#include "lantern/gi_texture_fetch.glsl"

// ---- the shading library's inputs

bool gi_has(int t) { return ((uint(pc.gi.y) >> uint(t)) & 1u) != 0u; }
vec4 gi_fetch(int t, ivec2 texel) { return gi_texture_fetch(t, texel.y * pc.gi.x + texel.x); }
// The vertex stage (the per-face wall-top light) looks at the neighbouring tiles too: it
// always asks the grid.
#ifdef LANTERN_GAME_WORLD_GRID_LOOKUP
bool gi_wall_tile(ivec2 tile) { return is_wall(tile); }
#else
bool gi_wall_tile(ivec2 tile) { return WALL_LOOKUP == 1 ? false : WALL_LOOKUP == 2 ? true : is_wall(tile); }
#endif
int gi_sun_count() { return pc.gi.z; }
GpuDirectionalLight gi_sun(int i) { return pc.suns[i]; }

// The light arriving at a wall box's top: the same for the whole face (the shading library's
// wall-top routing depends only on the tile), so the vertex stage computes it at the top's
// centre and the fragment stage takes it as it is. (Per pixel, its nine wall lookups and nine
// fetches made the whole frame's raster 2.5x slower on lavapipe; a compute pass per tile
// instead measured no faster than this, its dispatch costing what it saved.)
const bool WALL_TOP_PER_FACE = FACE == 4 && WALL_LOOKUP == 2;

void set_gi_shading() {
    gi_shading.window = pc.window;
    gi_shading.config = pc.config;
    gi_shading.options = pc.options;
}

#endif
