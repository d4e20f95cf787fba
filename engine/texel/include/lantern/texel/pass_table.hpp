// The texel passes as data (docs/texel.md, "The pass table"), the way docs/gi.md declares the
// GI's passes: each pass is one row (its name, what it reads and writes, the frame inputs it
// depends on, when it is not needed, its Vulkan recorder and its C++ reference), and one
// sequencer plans a frame from the rows:
//
//   TexelHistory history;                                // one per view, kept between frames
//   const TexelFrame frame{scene, lights};
//   const TexelPlan plan = plan_texel_frame(frame, history);
//   passes.record_plan(cmd, frame, plan);                // Vulkan (vulkan/texel_passes.hpp)
//   execute_reference(frame, plan, store);               // or the C++ reference
//
// A row's key is a hash of the inputs it lists and of the keys of the rows that wrote what
// it reads; a row runs when its key differs from the one its outputs were made with, and
// otherwise keeps them. So the bake reruns only when the layout, the walls, the static
// lights or a still placement change; UV to world reruns only for placements that moved
// (TexelPlan::moved); the realtime pass only when anything it reads changed (a flickering
// torch, the player walking), and a still scene submits nothing.
//
// Threads: the table is immutable; every function is safe from any thread. A TexelHistory
// is its owner's.
#pragma once

#include "lantern/texel/texel.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace lantern::texel {

enum class TexelPass : std::uint8_t { uv_to_world, bake, light, count };
inline constexpr int texel_pass_count = int(TexelPass::count);

// What the passes read and write: GPU storage buffers (TexelPasses), vectors on the reference.
enum class TexelData : std::uint8_t {
    scene,    // triangles, placements, normal maps, the wall patch (TexelScene)
    lights,   // the frame's lights
    surfaces, // per atlas texel: world position and normals (uv_to_world)
    baked,    // per atlas texel: the static lights' sum (the bake)
    lit,      // per atlas texel: saturate(live + baked), what the raster reads
};

// Frame inputs a row depends on (each a key input: texel_input_keys).
enum TexelInputBits : std::uint32_t {
    texel_input_layout = 1u << 0,        // the placements' models, atlas ranges, normal maps and which move
    texel_input_still_places = 1u << 1,  // where the still placements stand (their triangles)
    texel_input_moving_places = 1u << 2, // where the moving ones stand
    texel_input_walls = 1u << 3,         // the wall patch and the wall height
    texel_input_static_lights = 1u << 4, // the lights marked as_baked
    texel_input_lights = 1u << 5,        // every light
};
inline constexpr int texel_input_count = 6;

// One frame: the scene the passes read and its lights (as_baked ones baked for still
// placements). Both are the caller's and outlive the calls that take the frame.
struct TexelFrame {
    const TexelScene& scene;
    std::span<const TexelLight> lights;
    // The layout's key, when the caller has one (a hash of its models in placement order: the
    // game's parts): equal keys promise equal normal maps. 0: the sequencer hashes the scene's
    // normal maps, a cost per frame of the atlas's size (about 10 ns per texel here).
    std::uint64_t layout_key = 0;
};

using TexelKeys = std::array<std::uint64_t, texel_input_count>; // by input bit index
TexelKeys texel_input_keys(const TexelFrame& frame);

struct TexelRow {
    TexelPass pass = TexelPass::count;
    std::string_view name{}; // also the GPU timer's region name
    std::span<const TexelData> reads{};
    std::span<const TexelData> writes{};
    std::uint32_t inputs = 0; // TexelInputBits
    // nullptr when the row can run this frame, else why not.
    const char* (*not_needed)(const TexelFrame& frame) = nullptr;
};

// The rows in pipeline order (uv_to_world, bake, light).
std::span<const TexelRow> texel_rows();
const TexelRow& texel_row(TexelPass pass);

// What a frame runs.
struct TexelPlan {
    std::array<bool, texel_pass_count> run{};
    std::array<const char*, texel_pass_count> why_not{}; // rows not run: "unchanged", or not_needed's reason
    std::array<std::uint64_t, texel_pass_count> keys{};  // every row's key this frame
    // The scene data to upload first (the recorders' part: a Vulkan backend writes buffers).
    bool upload_layout = false;    // everything: normal maps, walls, triangles, placements
    bool upload_triangles = false; // triangles and placements (placements moved)
    bool upload_walls = false;     // the wall patch
    // uv_to_world for these placements only (ascending; empty with run[uv_to_world]: all).
    std::vector<std::uint32_t> moved;

    bool runs(TexelPass p) const { return run[std::size_t(p)]; }
};

// What the previous frames left (one per view): the keys the held outputs were made with,
// the inputs' keys, and each placement's triangles' hash (which of them moved).
struct TexelHistory {
    std::array<std::uint64_t, texel_pass_count> keys{}; // 0: nothing held
    TexelKeys inputs{};
    std::vector<std::uint64_t> placements;
    // Forget everything: every row runs next frame.
    void reset() { *this = {}; }
};

// Plans the frame and records it in `history` (the caller then runs the plan: a plan not
// run must be followed by history.reset()).
TexelPlan plan_texel_frame(const TexelFrame& frame, TexelHistory& history);

// ---- the reference backend

// The C++ reference's outputs, kept between frames as the GPU's buffers are.
struct TexelReferenceStore {
    std::vector<TexelSurface> surfaces;
    std::vector<glm::vec4> baked, lit;
};
// Runs the planned rows on the C++ reference (texel.hpp), as the Vulkan recorders do on the GPU.
void execute_reference(const TexelFrame& frame, const TexelPlan& plan, TexelReferenceStore& store);

// ---- light lists

// Which lights can reach each placement, for `pass` (the light pass's culling, shared by the
// backends): a point light whose range sphere misses the placement's bounding sphere adds
// nothing to any of its texels, nor does a baked light on a still placement in the realtime
// pass, and in the bake a moving placement takes no light. Lists keep the lights' order, so
// every texel's sum is the one over all lights, bit for bit.
// Layout: words [2k, 2k + 1] are placement k's first index and count; the indices follow.
std::vector<std::uint32_t> light_lists(const TexelScene& scene, std::span<const TexelLight> lights, LightPass pass);
// The same from the placements and whether each moves (placement_moves).
std::vector<std::uint32_t> light_lists(std::span<const GpuPlacement> placements, std::span<const std::uint8_t> moves,
                                       std::span<const TexelLight> lights, LightPass pass);

} // namespace lantern::texel
