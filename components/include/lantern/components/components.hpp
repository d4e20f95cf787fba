// The ECS components of a lit Lantern world. Plain data: systems (systems/) give them
// behaviour. Positions are world (x, z) on the ground plane, heights along y; colours are
// linear RGB and `intensity` multiplies them. Which systems read and write each component
// is in docs/frame.md.
#pragma once

#include "lantern/gi/passes.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace lantern {

// Where a non-light object stands (player, props, the camera's focus).
struct Transform {
    glm::vec3 position{0.0f};
};

// A shadow-casting point light (torches, lamps). Capped per frame by a stable priority.
struct PointLight {
    glm::vec2 position{0.0f};
    float height = 1.0f;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float radius = 8.0f;
    // realtime; mixed: direct light live, bounce from the bake; baked: all from the bake.
    // Honoured while the frame uses a bake (systems::BakedGi), else every light is realtime.
    scene::LightMode mode = scene::LightMode::realtime;
};

// A light without shadows (crystals, lava, spells); not capped.
struct EmissiveLight {
    glm::vec2 position{0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float radius = 4.0f;
    scene::LightMode mode = scene::LightMode::realtime; // as PointLight's
};

// Sun or moon.
struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // travel direction, need not be normalised
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float base_shadow_distance = 4.0f;
    float bounce_intensity = 0.5f;
    // With a bake in use: `mixed` keeps the direct light live and takes the bounce from the
    // bake (the `mixed` row lights it), `baked` leaves the live passes (docs/baked.md).
    scene::LightMode mode = scene::LightMode::realtime;
};

// An analytic occluder (trees, lamp posts, props): see scene::ShadowProxy for the fields.
struct ShadowProxy {
    scene::ShadowProxy shape;
};

// The camera the GI window follows: a top-down view or a perspective camera, with padding.
struct Camera {
    scene::ViewSpec view = scene::OrthoView{};
};

enum class ChunkState : std::uint8_t { loading, resident };

// A fixed-size block of the wall grid, resident around the GI window (systems/streaming).
// A chunk's bookkeeping. Its wall bytes live in one place: the Streaming resource's mirror
// (Streaming::is_wall, view), which the GPU buffer copies; edits of unloaded chunks are
// kept by Streaming too.
struct WallChunk {
    static constexpr int size = 32; // tiles per side
    glm::ivec2 coord{0};            // chunk coordinate: tiles [coord * size, coord * size + size)
    ChunkState state = ChunkState::loading;
    std::uint32_t version = 0;      // bumped on every edit of this chunk
};

// What the GI result held by the renderer was computed from: one key per pass (0 = never
// computed), and which passes the last frame ran or left out, and why.
struct GICache {
    std::array<std::uint64_t, gi::pass_count> keys{};
    gi::PassSet ran;          // last frame
    std::array<const char*, gi::pass_count> reason{}; // last frame, for passes that did not run
    std::uint64_t frames = 0;
};

} // namespace lantern
