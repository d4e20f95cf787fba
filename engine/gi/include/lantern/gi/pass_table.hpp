// GI methods as data (docs/gi.md, "The pass table").
//
// Every GI pass is one row: its name, the textures it reads and writes, the gi settings
// (keys of the scene format's one settings table) and the frame inputs it depends on, when
// it is needed, its Vulkan recorder and its C++ reference. A GI method (gi.method) is a named
// list of rows in pipeline order. One sequencer walks that list to
//   - plan a frame (plan_passes: which rows run, and why the others do not),
//   - choose the textures to allocate (textures_written: only what planned rows write),
//   - derive every cache key (derive_keys: inputs + listed settings + upstream keys), and
//   - record (vk::Renderer::record_plan) or execute (execute_reference) the planned rows.
// The backends (the Vulkan renderer, the reference, the frame runner, the frame systems)
// are thin adapters over these functions; the pass order is written once, in the method.
//
// Threads: the table is immutable after start-up; every function here is safe to call
// from any thread. The row functions run on the caller's thread (Vulkan recorders on the
// thread that records the command list).
#pragma once

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/gi/texture.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace lantern::gi {

// ---- textures --------------------------------------------------------------------------

enum class Tex : std::uint8_t {
    conduction,
    ao,
    direct,
    shadow,
    wall_direct_px,
    wall_direct_nx,
    wall_direct_pz,
    wall_direct_nz,
    emission,
    heat_a,
    heat_b,
    heat_mask, // 32-bit words: usable heat taps per heat texel (internal)
    indirect,
    blur_temp,
    wall_indirect_px,
    wall_indirect_nx,
    wall_indirect_pz,
    wall_indirect_nz,
    lit, // rgba8 sRGB, one 32-bit word per texel
    // Point and emissive light alone, when the scene has directional lights: the
    // directional pass reads these and writes direct/shadow/wall_direct_*, so either pass
    // can be rerun (or cached) without the other.
    direct_point,
    shadow_point,
    wall_direct_point_px,
    wall_direct_point_nx,
    wall_direct_point_pz,
    wall_direct_point_nz,
    count
};
inline constexpr int tex_count = int(Tex::count);

// The resolution a texture is allocated at.
enum class TexScale : std::uint8_t {
    window,    // the GI window: window.width x window.height
    heat_grid, // heat_grid(window, gi.heat_scale): full, half or quarter
};

struct TextureRow {
    Tex id;
    std::string_view name; // the --dump file stem ("wall_direct_px", ...)
    TexFormat format;
    TexScale scale = TexScale::window;
    bool words32 = false;  // stored as one 32-bit word per texel (the lit image, heat tap masks)
    bool internal = false; // scratch or intermediate: never read back, not a contract texture
};

const TextureRow& texture_row(Tex t);
const char* tex_name(Tex t);
std::optional<Tex> texture_by_name(std::string_view name);
// The size of `t` for this frame (its row's scale).
glm::ivec2 texture_size(Tex t, const FrameInputs& in);

struct TexSet {
    std::uint32_t bits = 0;
    bool has(Tex t) const { return (bits >> int(t)) & 1u; }
    TexSet& add(Tex t) {
        bits |= 1u << int(t);
        return *this;
    }
    friend bool operator==(TexSet, TexSet) = default;
};
static_assert(tex_count <= 32, "TexSet holds 32 textures");

// ---- rows ------------------------------------------------------------------------------

// Frame inputs a pass depends on besides textures and settings (each one a key input).
enum InputBits : std::uint32_t {
    input_walls = 1u << 0,           // the wall grid's bytes
    input_lights = 1u << 1,          // point and emissive lights
    input_proxies = 1u << 2,         // shadow proxies
    input_suns = 1u << 3,            // directional lights
    input_wall_height = 1u << 4,     // the scene's wall height
    input_walls_in_window = 1u << 5, // whether any wall lies in the window (plan.has_walls_in_window)
};

// The hashes of the frame inputs (the frame systems keep them as versions; input_keys_of
// hashes them from the inputs' contents).
struct InputKeys {
    std::uint64_t window = 0;
    std::uint64_t walls = 0;
    std::uint64_t lights = 0;
    std::uint64_t proxies = 0;
    std::uint64_t suns = 0;
};
InputKeys input_keys_of(const FrameInputs& in);

namespace vk {
class PassRecorder; // engine/gi/src/vulkan/pass_recorder.hpp
}

// What a reference row reads and writes: the textures of the frame by id (kept between
// frames by the reference backend) and the lit image.
struct ReferenceStore {
    std::array<std::optional<Texture>, tex_count> textures;
    std::optional<Image> lit;

    const Texture& at(Tex t) const;         // asserts that it exists
    const Texture* find(Tex t) const;       // nullptr when absent
    void put(Tex t, Texture texture);       // takes the row's name
    ShadingInputs shading_inputs(const FrameInputs& in) const;
};

struct ReferenceContext {
    const FrameInputs& in;
    const PassPlan& plan;
    const RefOptions& options;
    ReferenceStore& store;
};

struct PassRow {
    Pass pass = Pass::count;
    std::string_view name{};
    std::span<const Tex> reads{};  // textures read (an absent one reads as nothing)
    std::span<const Tex> writes{}; // textures written (allocated when the row is planned)
    // When set, replaces `writes` (outputs that depend on the frame: the direct pass writes
    // the point-light set when directional lights follow).
    TexSet (*writes_for)(const FrameInputs& in) = nullptr;
    std::span<const std::string_view> settings{}; // gi keys whose values change the output
    std::uint32_t inputs = 0;                    // InputBits
    // nullptr when the row is needed this frame, else why not ("no directional lights").
    const char* (*not_needed)(const FrameInputs& in, bool lit_image, bool walls_in_window) = nullptr;
    void (*record)(vk::PassRecorder& recorder) = nullptr;
    void (*reference)(ReferenceContext& context) = nullptr;

    TexSet outputs(const FrameInputs& in) const;
};

struct Method {
    scene::GiMethod id;
    std::string_view name;
    std::span<const PassRow* const> rows; // pipeline order
};

// The method of gi.method (every value of the setting has one).
const Method& method(scene::GiMethod id);
// The row of `pass` in the method that has it, or nullptr.
const PassRow* find_row(const Method& m, Pass pass);

// ---- the sequencer ----------------------------------------------------------------------

// The textures the planned rows write: what a backend allocates (the others it releases).
TexSet textures_written(const FrameInputs& in, const PassPlan& plan);

// Every pass's cache key (0 for passes not planned): a hash of the window, the inputs the
// row lists, the values of the settings it lists, the textures it writes, the keys of the
// planned rows that last wrote each texture it reads, and the own keys of later planned
// rows that overwrite its outputs in place (so that turning such a row on or off, or
// changing it, reruns the producer). A pass whose key is unchanged keeps last frame's
// outputs.
std::array<std::uint64_t, pass_count> derive_keys(const FrameInputs& in, const PassPlan& plan,
                                                  const InputKeys& inputs);
// The same for the rows of `m` (a method built in code: tests, methods of extensions).
std::array<std::uint64_t, pass_count> derive_keys(const Method& m, const FrameInputs& in, const PassPlan& plan,
                                                  const InputKeys& inputs);

// Runs the planned rows that are in `subset` on the C++ reference, in pipeline order;
// `timed` (optional) is called with each pass's start and end (now_ns()).
using PassTimer = void (*)(void* user, Pass pass, std::int64_t start_ns, std::int64_t end_ns);
void execute_reference(const FrameInputs& in, const PassPlan& plan, PassSet subset, const RefOptions& options,
                       ReferenceStore& store, PassTimer timed = nullptr, void* user = nullptr);
// Releases what the planned rows no longer write (as the Vulkan backend does).
void release_unwritten(const FrameInputs& in, const PassPlan& plan, ReferenceStore& store);

} // namespace lantern::gi
