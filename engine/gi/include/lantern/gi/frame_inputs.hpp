// Everything one GI frame reads, in the layout the GPU passes read it: the window, the wall
// grid, the gathered (culled and capped) lights and shadow proxies, and the settings.
//
// The light and proxy structs are mirrored in shaders/include/lantern/gi_types.glsl
// (std140 / std430-compatible: vec4 members only), hence alignas(16) and static_asserts.
#pragma once

#include "lantern/core/hash.hpp"
#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace lantern::gi {

struct alignas(16) GpuPointLight {
    glm::vec4 position_radius; // xy: world x, z; z: radius; w: unused
    glm::vec4 color;           // rgb: colour * intensity; a: unused
};
static_assert(sizeof(GpuPointLight) == 32);

struct alignas(16) GpuDirectionalLight {
    glm::vec4 direction_base;  // xyz: normalised travel direction; w: base shadow distance
    glm::vec4 color_multiplier; // rgb: colour * intensity; w: 1 / max(|direction.y|, 0.02)
    glm::vec4 bounce;           // x: bounce intensity; y: 1 for a mixed sun (mark_mixed); zw: unused
};
static_assert(sizeof(GpuDirectionalLight) == 48);

// A mixed sun while a bake is used (seed 004's mixed mode): its direct light is live, but
// added by the `mixed` row after the indirect rows, so the live bounce leaves it out (the
// bake holds its bounce), and it has no bounce fill. It stays in
// FrameInputs::directional_lights, so the raster, the probes and the texel lighting still see
// the sun; the `directional` row skips it.
inline bool is_mixed_sun(const GpuDirectionalLight& sun) { return sun.bounce.y != 0.0f; }
inline void mark_mixed(GpuDirectionalLight& sun) { sun.bounce = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f); }

struct alignas(16) GpuShadowProxy {
    glm::vec4 position_size; // xy: world x, z; zw: half extents (box) or radius in z (circle)
    glm::vec4 lengths;       // x: max length, y: end-cap blend, z: penumbra width, w: penumbra length
    glm::vec4 modes;         // x: penumbra power, y: shape (0 box, 1 circle), z: width mode, w: penumbra mode
    // x: strength in [0, 1], multiplying the proxy's occlusion (1: its whole shadow; 1 leaves
    // every result bit for bit as without it). The game's gathering fades proxies near its
    // cap (gather_offers_faded). yzw: 0.
    glm::vec4 fade{1.0f, 0.0f, 0.0f, 0.0f};
};
static_assert(sizeof(GpuShadowProxy) == 64);

// A wall material as the passes read it (scene::Material, docs/scenes.md "materials").
struct alignas(16) GpuMaterial {
    glm::vec4 albedo;   // rgb: reflectance; a: unused
    glm::vec4 emission; // rgb: radiosity the faces leave unlit; a: unused
};
static_assert(sizeof(GpuMaterial) == 32);
inline constexpr int material_table_size = 256; // one entry per wall cell value

// The wall grid as the passes read it: a width x height rectangle of tiles starting at world
// tile `origin`, stored toroidally so that a streaming world can move the rectangle and
// rewrite only the chunks that changed. Tile (x, z) inside the rectangle is
// cells[col + row * width] with col = (x - origin.x + phase.x) mod width (rows alike);
// tiles outside are air. A plain grid has phase (0, 0): cells[(x - origin.x) + ...].
struct WallView {
    const std::uint8_t* cells = nullptr; // width * height, 1 = wall
    int width = 0, height = 0;
    glm::ivec2 origin{0};
    glm::ivec2 phase{0}; // 0 <= phase < (width, height)

    static WallView of(const scene::WallGrid& g) {
        return WallView{g.cells.data(), g.width, g.height, g.origin, glm::ivec2(0)};
    }
    bool contains(int x, int z) const {
        const int c = x - origin.x, r = z - origin.y;
        return c >= 0 && r >= 0 && c < width && r < height;
    }
    std::size_t index(int x, int z) const {
        int c = x - origin.x + phase.x, r = z - origin.y + phase.y;
        if (c >= width) c -= width;
        if (r >= height) r -= height;
        return std::size_t(c) + std::size_t(r) * std::size_t(width);
    }
    bool is_wall(int x, int z) const { return contains(x, z) && cells[index(x, z)] != 0; }
    // The cell's value (0 air, else its wall material; scene.hpp), 0 outside.
    std::uint8_t cell(int x, int z) const { return contains(x, z) ? cells[index(x, z)] : std::uint8_t(0); }
};

// A byte range [begin, end) of a WallView's cells that changed.
struct WallRange {
    std::size_t begin = 0, end = 0;
};

struct FrameInputs {
    GiWindow window;
    WallView walls;
    float wall_height = 2.0f;
    scene::GiSettings settings;
    std::vector<GpuPointLight> point_lights; // culled to the window, capped at max_lights
    std::vector<GpuPointLight> emissive_lights; // culled, not capped
    // Mixed lights while a bake is used (`baked`): their direct light is live, added by the
    // `mixed` row after the indirect rows so that the live bounce leaves them out (the bake
    // holds their bounce). Culled as the others; without a bake mixed lights are realtime.
    std::vector<GpuPointLight> mixed_lights, mixed_emissives;
    // Every sun that shines; the mixed ones marked (is_mixed_sun), lit by the `mixed` row.
    std::vector<GpuDirectionalLight> directional_lights;
    std::vector<GpuShadowProxy> proxies; // culled by reach, closest max_shadow_proxies kept
    // Scene indices of what was kept, in the order above (tests and the HUD use them).
    std::vector<std::uint32_t> point_light_ids, emissive_ids, proxy_ids;
    // The scene's wall materials: cell value 2 + k is materials[k]. Cell value 1, and a value
    // past the list, is the default wall: grey settings.wall_albedo, no emission. Empty: every
    // wall is the default. Part of the walls' input key.
    std::vector<GpuMaterial> materials;
    // The bake's light over part of the world (docs/baked.md, "At run time"), added to the
    // indirect textures by the `baked` row; nullptr: none. The live lights and materials
    // then leave out what it holds (bake::live_scene).
    std::shared_ptr<const BakedLight> baked;
    // Seed 004's pulsing emission: the factor the bake's pulsing part is added with
    // (scene::pulse_factor of the scene's pulse frequency at the frame's time; 1 = the glow
    // at full emission). Read only when `baked` is pulsing; a change reruns the baked rows
    // (a colour-only update, not a re-bake): a change reruns the baked pass's adds.
    float baked_pulse = 1.0f;
};

// Whether the frame has suns the `directional` row lights (realtime ones), and mixed ones.
bool has_live_suns(const FrameInputs& in);
bool has_mixed_suns(const FrameInputs& in);
// Whether every proxy's penumbra power is exactly 1 (the shaders' LINEAR_PENUMBRA; true
// without proxies).
bool penumbras_linear(const FrameInputs& in);
// The frame with only its realtime suns (mixed = false) or only its mixed ones.
FrameInputs with_suns(const FrameInputs& in, bool mixed);

// A frame that needs shader variants a later frame of `in`'s session may need and `in` may
// not: `in` with, at the window's centre, a point light when it has none, a mixed one when a
// bake is used and it has none, a realtime sun when it has none, a mixed sun when the bake
// has sun keys and it has none, and a shadow proxy when it has none. docs/performance.md,
// "Hitches on a fresh machine": llvmpipe generates a shader's code at its first dispatch, so
// the game records such a frame once at start-up, before play
// (systems::GiFrameOptions::warm_up_shaders).
FrameInputs warm_up_inputs(const FrameInputs& in);

// The material of a wall cell value (0, air: all zero).
GpuMaterial material_of(const FrameInputs& in, std::uint8_t cell);
// Every cell value's material, for the GPU (material_table_size entries).
std::vector<GpuMaterial> material_table(const FrameInputs& in);
// Whether any material the walls can hold emits light.
bool has_emissive_materials(const FrameInputs& in);
GpuMaterial pack_material(const scene::Material& m);

// Distance from p to the window's world rectangle (0 inside).
float distance_to_window(const GiWindow& window, glm::vec2 p);

// ---- gathering: the one road from lights to the GPU ------------------------------------
// The game's gathering systems (systems/gi_frame.cpp, over ECS components) and the scene
// path below (tools, benchmarks, tests) both choose and pack what a frame sees with these.

// A light or shadow proxy offered to a frame: where it stands, how far it reaches, its
// order (scene index or entity rank: the GPU order and the last tie-break) and a priority
// bonus (hysteresis: kept last frame).
struct Offer {
    glm::vec2 position{0.0f};
    float reach = 0.0f;
    std::uint32_t order = 0;
    float bonus = 0.0f;
};
// The offers that reach the window (distance to it <= reach); when more than `cap` do, the
// `cap` of smallest (distance to the window centre - bonus, order) are kept. Returned as
// indices into `offers`, by order (so sums on the GPU do not depend on priorities).
std::vector<std::uint32_t> gather_offers(const std::vector<Offer>& offers, const GiWindow& window, std::size_t cap);

// As gather_offers, with a fade in [0, 1] per kept offer (same order as `ids`): 1 while no
// more than `cap` offers reach the window; otherwise (p_cut - p) / band, clamped, where p is
// an offer's priority (distance to the window centre - bonus) and p_cut the priority of the
// first offer cut. An offer nearing the cut fades out over the last `band` world units of
// priority, so it leaves the set (or enters it) at strength 0 instead of popping; p_cut moves
// continuously as the window does. band <= 0: every fade is 1.
struct FadedOffers {
    std::vector<std::uint32_t> ids;
    std::vector<float> fade;
};
FadedOffers gather_offers_faded(const std::vector<Offer>& offers, const GiWindow& window, std::size_t cap, float band);

// How far a proxy's shadow reaches: max(size) + max_length + max(penumbra_width,
// penumbra_length).
float proxy_reach(const scene::ShadowProxy& proxy);
GpuPointLight pack_light(glm::vec2 position, glm::vec3 color, float intensity, float radius);
GpuShadowProxy pack_proxy(const scene::ShadowProxy& proxy, float strength = 1.0f);
// The sun's bounce fill (bounce_intensity, seed 000's stylised light in its own shadows) is
// left out (0) under a method whose bounce light is physical (gi.method = gather): it
// carries the sun's bounces itself.
GpuDirectionalLight pack_directional(const scene::DirectionalLight& light,
                                     scene::GiMethod method = scene::GiMethod::heat);
// A dark sun (the night side of a day cycle) adds nothing and is left out, so the
// directional pass does not run for it.
bool sun_adds_light(glm::vec3 color, float intensity);

// The frame as it is lit with a bake of `scene` (FrameInputs::baked): the mixed lights move
// to mixed_lights / mixed_emissives, mixed suns are marked (mark_mixed), the baked lights
// leave (by the scene indices in point_light_ids / emissive_ids and the suns' order, so call
// it on gather_frame_inputs' result for the same scene).
void split_for_bake(FrameInputs& in, const scene::Scene& scene);

// A scene's lights and proxies for a window, chosen as the game's gathering systems choose
// them (gather_offers): point lights and emissives are kept when their radius reaches the
// window (even if they stand outside it), point lights beyond max_lights by priority
// (distance to the window centre, then scene order); proxies when their reach touches the
// window, the closest max_shadow_proxies kept; suns unless dark.
FrameInputs gather_frame_inputs(const scene::Scene& scene, const GiWindow& window);

} // namespace lantern::gi

namespace lantern {
// vec4 members only, sizes asserted above: no padding, so cache keys hash them as bytes.
template <>
inline constexpr bool hash_as_bytes<gi::GpuPointLight> = true;
template <>
inline constexpr bool hash_as_bytes<gi::GpuDirectionalLight> = true;
template <>
inline constexpr bool hash_as_bytes<gi::GpuShadowProxy> = true;
template <>
inline constexpr bool hash_as_bytes<gi::GpuMaterial> = true;
} // namespace lantern
