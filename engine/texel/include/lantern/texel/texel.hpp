// Per-texel lighting of models (seed 001, "Per Texel Lighting"; docs/texel.md).
//
// A model's light is computed once per texel of its texture rather than per pixel on the
// screen, so light changes across it in steps of the art's texels. Two passes, each a
// compute shader (shaders/texel_*.comp.glsl) with the C++ reference here:
//
//   uv_to_world   once per model placement (again when its transform changes): every texel
//                 of the texture found in the model's triangles in UV space (barycentric
//                 coordinates, the seed's eps leniency, the first triangle in index order
//                 wins), then carried to the triangle in the world: position, the normal
//                 bent by the normal map, and the triangle's own (geometric) normal.
//   light         per frame: every used texel against every light in range, the seed's term
//                 ((1 - d / range) |cos|)^2 x colour, shadowed by the wall grid (the seed-000
//                 DDA lifted to wall columns of the world's wall height: always hard) and by
//                 every other model's triangles (the seed's occluder rules, per light: none,
//                 hard, or blurred by blur = (NLR / LR)^power x multiplier), plus each
//                 light's ambient colour falling off with its range. Static lights are baked
//                 once (mode bake); each frame's realtime result is then
//                 saturate(realtime + baked), the seed's Apply step.
//
// Coordinates: the world is Lantern's (x, z the ground plane in tiles, y up). A texture of
// `size` texels has texel (x, y) (row y from the top) at UV ((x + 0.5) / size, (y + 0.5) /
// size): texel centres (the seed used corners). Texels of every placement sit end to end in
// one array ("the atlas"): placement k's texel (x, y) is atlas index first_texel + y * size + x.
//
// The GPU structs below are the shaders' std430 layouts (vec4 members only).
#pragma once

#include "lantern/gi/frame_inputs.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace lantern::texel {

// The seed's leniency of the inside-triangle tests (barycentric units).
inline constexpr float inside_eps = 1e-3f;

// ---- models ---------------------------------------------------------------------------------

// A triangle of a model: object-space corners and their UVs ([0, 1], v down the texture).
struct ModelTriangle {
    glm::vec3 p[3]{};
    glm::vec2 uv[3]{};
};

// A model: its triangles and a square texture of `size` texels per side. The normal map is
// stored as a normal-map texture holds it (rgb in [0, 1], green up the image); empty: flat.
// Albedo is what the raster multiplies the light by (linear rgb); the passes do not read it.
struct Model {
    int size = 0;
    std::vector<ModelTriangle> triangles;
    std::vector<glm::vec4> albedo;     // size * size, or empty
    std::vector<glm::vec4> normal_map; // size * size, or empty (flat: (0.5, 0.5, 1))
    // box_model's faces (+x, -x, +z, -z, top): each one's texel rectangle (x, y, width,
    // height; row y from the top). Face f's texel (i, j) counts i along its `right` and j
    // down from its top edge, seen from outside: +x right is -z, -x +z, +z +x, -z -x (up +y);
    // the top's right is +x and its up -z. Empty for other models.
    std::vector<glm::ivec4> faces;
};

// An axis-aligned box standing on its footprint: the four sides and the top (the bottom is
// on the ground and never seen), each face a rectangle of the texture `texels_per_unit`
// texels per world unit (at least one texel), packed in rows with a one-texel gutter into
// the smallest square texture that holds them. Two triangles per face; the faces
// wind counter-clockwise seen from outside (normals point out).
Model box_model(glm::vec3 min, glm::vec3 max, int texels_per_unit);
// Appends `b`'s triangles to `a` with their UVs scaled into the texture rectangle
// [origin, origin + extent) (UV units) of `a`; both textures are the caller's to fill.
void append_triangles(Model& a, const Model& b, const glm::mat4& transform, glm::vec2 origin, glm::vec2 extent);

// ---- the passes' inputs ----------------------------------------------------------------------

// A world-space triangle (128 bytes).
struct alignas(16) GpuTriangle {
    glm::vec4 p1{0.0f}, p2{0.0f}, p3{0.0f}; // xyz world; w unused
    glm::vec4 uv12{0.0f};                   // xy uv of p1, zw uv of p2
    glm::vec4 uv3{0.0f};                    // xy uv of p3; z its placement; w 1: it moves (Placement::moves)
    glm::vec4 normal{0.0f};                 // unit, from the winding: cross(p2 - p1, p3 - p1)
    glm::vec4 tangent{0.0f};                // unit, along +u in the world
    glm::vec4 binormal{0.0f};               // unit, along +v (down the texture) in the world
};
static_assert(sizeof(GpuTriangle) == 128);

// A model placed in the world (32 bytes).
struct alignas(16) GpuPlacement {
    glm::uvec4 ranges{0u}; // x first triangle, y triangle count, z first texel, w texture size
    glm::vec4 bounds{0.0f}; // xyz centre, w radius of a sphere holding its triangles
};
static_assert(sizeof(GpuPlacement) == 32);

// A texel carried into the world by uv_to_world (48 bytes).
struct alignas(16) TexelSurface {
    glm::vec4 position_used{0.0f};   // xyz world; w 1 when the texel lies on a triangle, else 0
    glm::vec4 normal_triangle{0.0f}; // xyz the normal-mapped normal (unit); w its triangle (index)
    glm::vec4 geo_normal{0.0f};      // xyz the triangle's normal
};
static_assert(sizeof(TexelSurface) == 48);

enum class ShadowType : int { none = 0, hard = 1, blurred = 2 };

// A light of the texel passes (64 bytes): a point light, or a directional one (a sun).
//   point        xyz its position; w its range (> 0): the seed's term and linear ambient falloff
//   directional  xyz its unit direction of travel (y < 0: from above); w how far towards it
//                shadows are looked for (tiles); no falloff: ((|cos|)^2 x colour, ambient whole)
struct alignas(16) TexelLight {
    glm::vec4 position_range{0.0f}; // see above
    glm::vec4 color_type{0.0f};     // rgb colour x intensity; w float(ShadowType)
    glm::vec4 blur{1.0f, 1.0f, 0.0f, 0.0f}; // x multiplier, y power (blurred shadows); z 1: directional;
                                            // w 1: baked (see as_baked)
    glm::vec4 ambient{0.0f};        // rgb ambient colour at the light (point: falling to 0 at range)
};
static_assert(sizeof(TexelLight) == 64);

TexelLight make_light(glm::vec3 position, glm::vec3 color, float intensity, float range,
                      ShadowType shadow = ShadowType::hard, float blur_multiplier = 1.0f, float blur_power = 1.0f,
                      glm::vec3 ambient = glm::vec3(0.0f));
// A sun travelling along `direction` (normalised here; y < 0 shines down). Its shadows are
// looked for up to `reach` tiles towards it: walls until the ray clears their tops, models
// over the whole reach (NLR / LR with LR = reach for blurred ones).
TexelLight make_sun(glm::vec3 direction, glm::vec3 color, float intensity, ShadowType shadow = ShadowType::hard,
                    float reach = 48.0f, glm::vec3 ambient = glm::vec3(0.0f));
bool is_directional(const TexelLight& light);
// The seed's static light: baked into baked() by the bake pass (for still placements), so
// the realtime pass skips it there and adds it only on placements that move. The bake pass
// reads every light it is given, marked or not.
inline TexelLight as_baked(TexelLight light) {
    light.blur.w = 1.0f;
    return light;
}
inline bool is_baked(const TexelLight& light) { return light.blur.w > 0.5f; }

// The wall grid as the light pass reads it: a plain (untoroidal) rectangle of cells, four
// per 32-bit word (byte i of word i / 4), tiles outside it air.
struct WallPatch {
    glm::ivec2 origin{0};
    int width = 0, height = 0;
    std::vector<std::uint32_t> words;
    bool is_wall(int x, int z) const;
};

// Everything the passes read but the lights.
struct TexelScene {
    std::vector<GpuTriangle> triangles;   // every placement's, in placement order
    std::vector<GpuPlacement> placements; // first texels ascending, no gaps
    std::vector<glm::vec4> normal_maps;   // per atlas texel, encoded as in Model (flat filled in)
    std::uint32_t texel_count = 0;
    WallPatch walls;
    float wall_height = 2.0f;
};

struct Placement {
    const Model* model = nullptr;
    glm::mat4 transform{1.0f}; // object to world (rigid or scaled; normals are transformed
                               // as directions and renormalised)
    // A placement that moves between bakes (the player): the bake leaves it out, as a
    // receiver (its baked light stays 0) and as an occluder, and the realtime pass lights it
    // with every light, baked ones included. Still placements take baked lights from the bake.
    bool moves = false;
};

// Places the models; `walls` is copied over the placements' bounds grown by `reach` tiles
// (the longest light range the frames will use: every cell a shadow ray can cross).
TexelScene build_scene(std::span<const Placement> placements, const gi::WallView& walls, float wall_height,
                       float reach);
// Whether placement `p` of `scene` moves (its triangles carry Placement::moves).
bool placement_moves(const TexelScene& scene, const GpuPlacement& p);
// Replaces placement `index`'s triangles for a new transform (its texels' surfaces must then
// be recomputed: uv_to_world_placement / record_uv_to_world).
void move_placement(TexelScene& scene, std::uint32_t index, const Model& model, const glm::mat4& transform);

// ---- the C++ reference ----------------------------------------------------------------------

// The seed's loop: every texel against every triangle of its placement, the first containing
// it wins. O(texels x triangles).
std::vector<TexelSurface> uv_to_world_brute(const TexelScene& scene);
// The same result by scanning each triangle's bounding rectangle of texels (O(texels
// covered)): bit for bit what the brute force finds (tests/texel).
std::vector<TexelSurface> uv_to_world(const TexelScene& scene);
void uv_to_world_placement(const TexelScene& scene, std::uint32_t index, std::span<TexelSurface> surfaces);


// 1 when nothing of the wall grid stands between `light` and `point`, else 0: the DDA of the
// seed-000 direct pass (gi::shadow_dda: its bias and corner rule) over the xz projection, a
// wall cell blocking when the segment is below the wall height where it enters or leaves
// the cell (the lowest point of a straight segment over a cell is at one of those). With
// both ends below the wall height it is gi::shadow_dda.
float wall_visibility(const WallPatch& walls, float wall_height, glm::vec3 light, glm::vec3 point);

// The seed's occluder test from `origin` (a point light's position, or the point a sun's
// shadow search starts from) towards `point`, against every triangle but `own` (placements
// whose bounding sphere the segment misses are skipped): 1 lit; hard: 0 at the first hit;
// blurred: clamp((NLR / LR)^power x multiplier, 0, 1), NLR the distance from `point` to the
// nearest hit, LR the distance to `origin`. Occluders that face away from the light (or are
// edge-on) and hits at or beyond the texel are skipped. `light` gives the shadow type and blur.
// `still_only`: placements that move cast no shadow (the bake's rule).
float occluder_visibility(const TexelScene& scene, const TexelLight& light, glm::vec3 origin, glm::vec3 point, int own,
                          bool still_only = false);
// A sun's grid and occluder shadow at `point` (1 lit, 0 shadowed, between: blurred).
float sun_visibility(const TexelScene& scene, const TexelLight& sun, glm::vec3 point, int own, bool still_only = false);

// Which pass a texel's light is summed for. bake: placements that move receive nothing and
// cast no shadow (their light is all realtime); realtime: baked lights (as_baked) are left out
// on still placements, whose baked() holds them.
enum class LightPass { bake, realtime };

// The light (rgb) at one texel from `lights`, ambient included.
glm::vec3 texel_light(const TexelScene& scene, std::span<const TexelLight> lights, const TexelSurface& s,
                      LightPass pass = LightPass::realtime);

// Every texel's light: with `baked` empty the bake's raw sums (rgb, a 1 on used texels of
// still placements), else the realtime pass's saturate(sum + baked) (the seed's Apply).
// Unused texels are 0.
std::vector<glm::vec4> reference_light(const TexelScene& scene, std::span<const TexelSurface> surfaces,
                                       std::span<const TexelLight> lights, std::span<const glm::vec4> baked = {});

} // namespace lantern::texel
