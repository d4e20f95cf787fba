// GI methods as data (docs/gi.md, "The pass table").
//
// Every GI pass is one row: its name, the textures it reads and writes, the gi settings
// (keys of the scene format's one settings table) and the frame inputs it depends on, when
// it is needed, how often it repeats, whether it converges over frames, its Vulkan recorder
// and its C++ reference. A GI method (gi.method) is a named list of rows in pipeline order.
// One sequencer walks that list to
//   - plan a frame (plan_passes: which rows run, and why the others do not),
//   - choose the textures to allocate (textures_written: only what planned rows write),
//   - derive every cache key (derive_keys: inputs + listed settings + upstream keys, and
//     the history of converging rows), and
//   - record (vk::Renderer::record_plan) or execute (execute_reference) the planned rows.
// The backends (the Vulkan renderer, the reference, the frame runner, the frame systems)
// are thin adapters over these functions; the pass order is written once, in the method.
//
// Code outside the engine adds textures and rows at start-up (add_texture, add_row): a new
// pass is a shader, a reference function and one row (docs/gi.md, "A new pass").
//
// Threads: add_texture and add_row run at start-up, before any frame is planned, on one
// thread; after that the table is immutable and every function here is safe to call from
// any thread. The row functions run on the caller's thread (Vulkan recorders on the thread
// that records the command list).
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/gi/texture.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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
    // The realtime suns' light alone (the directional pass writes it; shadow: G only): the
    // direct pass adds it to the point and emissive lights' as it writes the contract set, so
    // the suns' pass reruns only when a sun, the walls, the proxies or the window change, and
    // the point lights' only when they do (docs/gi.md, "The suns' own textures").
    direct_sun,
    shadow_sun,
    wall_direct_sun_px,
    wall_direct_sun_nx,
    wall_direct_sun_pz,
    wall_direct_sun_nz,
    // gi.proxy_wall_shadows = unfold, with shadow proxies: per face the light at the top of
    // the face (rgb) and the height where the proxies' shadows end (a, world units); the
    // wall_direct_* textures then hold the light at the face's foot.
    wall_upper_px,
    wall_upper_nx,
    wall_upper_pz,
    wall_upper_nz,
    wall_upper_sun_px, // the realtime suns' part
    wall_upper_sun_nx,
    wall_upper_sun_pz,
    wall_upper_sun_nz,
    // gi.method = radiosity (seed 003), on the radiosity grid (gi.radiosity.scale):
    jfa_a, // jump flood ping-pong: the nearest wall texel's coordinate (internal)
    jfa_b,
    distance_field, // rgba16f: distance to the nearest wall texel (grid texels), unit direction to it
    distance_steps, // 32-bit words: floor(256 x distance), what the raymarch steps by (internal)
    radiosity_light, // this frame's emitters: the direct light + feedback x last frame's (internal)
    radiosity,       // the raymarched light, accumulated over frames
    // gi.method = gather (physical):
    gather_face_a, // indirect irradiance per wall-face texel, face f at rows f x height.. (internal)
    gather_face_b, // its ping-pong partner (face bounces alternate between the two)
    gather_ground, // the ground's indirect fluence on the gather grid (gi.gather.scale)
    // The mixed lights' direct light (a bake is used: docs/baked.md), the direct pass's
    // outputs for them alone, kept while they stay put; the baked pass adds them (internal).
    direct_mixed,
    shadow_mixed,
    wall_direct_mixed_px,
    wall_direct_mixed_nx,
    wall_direct_mixed_pz,
    wall_direct_mixed_nz,
    wall_upper_mixed_px,
    wall_upper_mixed_nx,
    wall_upper_mixed_pz,
    wall_upper_mixed_nz,
    // The mixed suns' part alone (the mixed row writes it beside the mixed lights' set, so a
    // moving mixed sun leaves the mixed lights' bins be; the baked pass adds both; internal).
    direct_mixed_sun,
    shadow_mixed_sun,
    wall_direct_mixed_sun_px,
    wall_direct_mixed_sun_nx,
    wall_direct_mixed_sun_pz,
    wall_direct_mixed_sun_nz,
    wall_upper_mixed_sun_px,
    wall_upper_mixed_sun_nx,
    wall_upper_mixed_sun_pz,
    wall_upper_mixed_sun_nz,
    // What the baked pass added, for the HUD's views (docs/baked.md): rgb the baked light
    // alone (open ground: the ground's; a wall texel: its exposed faces'), a the level + 1 of
    // the brick it came from (0: none).
    baked_view,
    // The baked light the baked pass adds, read from the atlas by the sampling pass and kept
    // while the bake and the window stand still (internal): the ground's, each face's.
    baked_ground,
    baked_face_px,
    baked_face_nx,
    baked_face_pz,
    baked_face_nz,
    // The pulsing glow's part of it at pulse 1 (BakedLight::pulsing), kept alike: the baked pass
    // adds it scaled by this frame's pulse, so a new pulse reads no atlas (internal).
    baked_pulse_ground,
    baked_pulse_face_px,
    baked_pulse_face_nx,
    baked_pulse_face_pz,
    baked_pulse_face_nz,
    // Live light probes (probes.hpp): five texels a probe, every other tile of the window.
    probes,
    builtin_count
};
// Texture ids: the built-ins above, then textures added at run time (add_texture) up to
// this capacity. Arrays indexed by Tex have tex_count entries.
inline constexpr int tex_count = 128;
inline constexpr int builtin_tex_count = int(Tex::builtin_count);

// The resolution a texture is allocated at.
enum class TexScale : std::uint8_t {
    window,    // the GI window: window.width x window.height
    heat_grid, // heat_grid(window, gi.heat_scale): full, half or quarter
    custom,    // TextureRow::size(in): cascade levels, probe atlases, plain buffers (height 1)
};

// A texture is a GPU buffer of pitch x height texels (pitch = width rounded up to 4) and a
// C++ Texture on the reference. A plain buffer (a probe atlas, a list) is a words32 texture
// of custom size: one 32-bit word per element, width x height elements.
struct TextureRow {
    Tex id = Tex::builtin_count;
    std::string_view name{}; // the --dump file stem ("wall_direct_px", ...); static storage
    TexFormat format = TexFormat::rgba16f;
    TexScale scale = TexScale::window;
    bool words32 = false;  // stored as one 32-bit word per texel (the lit image, heat tap masks)
    bool internal = false; // scratch or intermediate: never read back, not a contract texture
    glm::ivec2 (*size)(const FrameInputs& in) = nullptr; // TexScale::custom
};

const TextureRow& texture_row(Tex t);
const char* tex_name(Tex t);
std::optional<Tex> texture_by_name(std::string_view name);
// Texture ids in use: 0 .. registered_texture_count() - 1.
int registered_texture_count();
// The contract textures (not internal) for which `held(t)` is true, in table order: what a
// backend lists, reads back and dumps.
template <typename Held>
std::vector<Tex> contract_textures(Held&& held) {
    std::vector<Tex> out;
    for (int t = 0; t < registered_texture_count(); ++t)
        if (!texture_row(Tex(t)).internal && held(Tex(t))) out.push_back(Tex(t));
    return out;
}
// The size of `t` for this frame (its row's scale).
glm::ivec2 texture_size(Tex t, const FrameInputs& in);

// A set of texture ids, one bit each.
struct TexSet {
    static constexpr int word_bits = 64;
    std::array<std::uint64_t, tex_count / word_bits> words{};

    bool has(Tex t) const { return (words[std::size_t(int(t) / word_bits)] >> (int(t) % word_bits)) & 1u; }
    TexSet& add(Tex t) {
        words[std::size_t(int(t) / word_bits)] |= std::uint64_t(1) << (int(t) % word_bits);
        return *this;
    }
    TexSet& operator|=(const TexSet& o) {
        for (std::size_t i = 0; i < words.size(); ++i) words[i] |= o.words[i];
        return *this;
    }
    bool intersects(const TexSet& o) const {
        for (std::size_t i = 0; i < words.size(); ++i)
            if (words[i] & o.words[i]) return true;
        return false;
    }
    bool empty() const {
        for (std::uint64_t w : words)
            if (w) return false;
        return true;
    }
    // Calls f(Tex) for each member, in id order.
    template <typename F>
    void for_each(F&& f) const {
        for (std::size_t i = 0; i < words.size(); ++i)
            for (std::uint64_t w = words[i]; w; w &= w - 1)
                f(Tex(int(i) * word_bits + std::countr_zero(w)));
    }
    friend bool operator==(const TexSet&, const TexSet&) = default;
};
static_assert(tex_count % TexSet::word_bits == 0, "TexSet holds whole words");

// ---- rows ------------------------------------------------------------------------------

// Frame inputs a pass depends on besides textures and settings (each one a key input).
enum InputBits : std::uint32_t {
    input_walls = 1u << 0,           // the wall grid's bytes
    input_lights = 1u << 1,          // point and emissive lights
    input_proxies = 1u << 2,         // shadow proxies
    input_suns = 1u << 3,            // directional lights
    input_wall_height = 1u << 4,     // the scene's wall height
    input_walls_in_window = 1u << 5, // whether any wall lies in the window (plan.has_walls_in_window)
    input_baked = 1u << 6,           // the baked light (FrameInputs::baked, its key)
    input_mixed_lights = 1u << 7,    // the mixed lights (FrameInputs::mixed_lights, mixed_emissives)
    input_baked_pulse = 1u << 8,     // the pulsing glow's factor (FrameInputs::baked_pulse) when the bake pulses
    input_mixed_suns = 1u << 9,      // the mixed suns alone (the mixed row: a realtime sun's move leaves it be)
};

// The hashes of the frame inputs (the frame systems keep them as versions; input_keys_of
// hashes them from the inputs' contents).
struct InputKeys {
    std::uint64_t window = 0;
    std::uint64_t walls = 0;
    std::uint64_t lights = 0;
    std::uint64_t proxies = 0;
    std::uint64_t suns = 0;
    std::uint64_t baked = 0; // FrameInputs::baked->key, 0 without
    std::uint64_t mixed = 0; // the mixed lights
    std::uint64_t baked_pulse = 0; // the pulsing glow's factor, 0 without a pulsing bake
    std::uint64_t mixed_suns = 0;  // the mixed suns (mixed_suns_key)
};
InputKeys input_keys_of(const FrameInputs& in);
// InputKeys::baked of a frame: the baked light's key, with the keyed sun's keys, blend and
// colour when the bake has sun keys (so a moving sun reruns the baked rows); 0 without a bake.
std::uint64_t baked_input_key(const FrameInputs& in);
// InputKeys::baked_pulse: the pulsing glow's factor when the bake has a pulsing part (a new
// pulse reruns the baked pass's adds, not the atlas reads); 0 otherwise.
std::uint64_t baked_pulse_key(const FrameInputs& in);
// InputKeys::mixed_suns: a hash of the mixed suns alone (is_mixed_sun), in order.
std::uint64_t mixed_suns_key(const FrameInputs& in);

namespace vk {
class PassRecorder; // lantern/gi/vulkan/pass_recorder.hpp
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
    int iteration = 0; // 0 .. iterations - 1 (PassRow::iterations)
    int history = 0;   // converging rows: frames accumulated before this one (plan.history)
};

// A shader library's lookup (the function lantern_add_shader_library generates):
// the SPIR-V of "<name>.<stage>", empty when the library has no such shader.
using ShaderLookup = std::span<const std::uint32_t> (*)(std::string_view name);

struct PassRow {
    Pass pass = Pass::builtin_count;
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
    // How many times the row runs in a frame (heat rounds, jump-flood steps, cascade
    // levels): record/reference are called once per iteration, each seeing its index
    // (PassRecorder::iteration, ReferenceContext::iteration). nullptr: once.
    int (*iterations)(const FrameInputs& in) = nullptr;
    // A converging row (temporal accumulation, bounce feedback) runs every frame until it
    // has accumulated converge_frames(in) frames since its inputs last changed; its key
    // includes the frame index until then, so it and the rows downstream rerun, and a
    // still scene then stops submitting. Its outputs persist between frames (both backends
    // keep every texture); history 0 means "start afresh". nullptr: not converging.
    int (*converge_frames)(const FrameInputs& in) = nullptr;
    // A converging row's reads whose changes rerun it (and restart its count towards
    // converge_frames) but keep its history: bounce feedback goes on from last frame's light
    // when a light moves. Changes to anything else it depends on start it afresh.
    std::span<const Tex> history_keeps{};
    void (*record)(vk::PassRecorder& recorder) = nullptr;
    void (*reference)(ReferenceContext& context) = nullptr;
    // Where the recorder's shaders come from; nullptr: the engine's lantern_gi_shaders.
    ShaderLookup shaders = nullptr;

    TexSet outputs(const FrameInputs& in) const;
    int iteration_count(const FrameInputs& in) const { return iterations ? iterations(in) : 1; }
};

struct Method {
    scene::GiMethod id;
    std::string_view name;
    std::span<const PassRow* const> rows; // pipeline order
};

// The method of gi.method (every value of the setting has one).
const Method& method(scene::GiMethod id);
// Every method, in the order of scene::GiMethod (the HUD's choice).
std::vector<const Method*> methods();
// The row of `pass` in the method that has it, or nullptr.
const PassRow* find_row(const Method& m, Pass pass);
// The registered row of `pass` (any method), or nullptr.
const PassRow* find_row(Pass pass);

// ---- extensions (start-up only; see "Threads" above)

// Adds a texture; its id is assigned (row.id is ignored). Errors: the name is taken or not
// a file stem, a custom scale without a size function, the table is full.
Result<Tex> add_texture(TextureRow row);
// Adds `row` to method `m` right after the row of `after`; its id is assigned (row.pass is
// ignored) and returned. The row is copied; the spans it points at must be static. Errors:
// `after` is not in the method, a listed setting is not a gi key, a texture id is not
// registered, the name is taken, no record or reference function, the table is full.
Result<Pass> add_row(scene::GiMethod m, Pass after, PassRow row);

// ---- the sequencer ----------------------------------------------------------------------

// The textures the planned rows write: what a backend allocates (the others it releases).
TexSet textures_written(const FrameInputs& in, const PassPlan& plan);

// Memory is estimated before it is allocated: the bytes of the textures the planned rows
// write, as the GPU stores them (8 bytes per rgba16f texel, pitch rounded up to 4) or as
// the reference does (a float per channel), and a documented budget for each (docs/gi.md,
// "Memory budget"). check_texture_budget refuses a frame over it with one line naming the
// need and the limit (exit code 2) before a backend allocates anything.
enum class TextureStorage : std::uint8_t { gpu, reference };
inline constexpr std::uint64_t max_gi_texture_bytes = std::uint64_t(2) << 30; // 2 GiB, either storage
std::uint64_t texture_bytes(const FrameInputs& in, const PassPlan& plan, TextureStorage storage);
Result<void> check_texture_budget(const FrameInputs& in, const PassPlan& plan, TextureStorage storage);

// The history of the converging rows between frames, kept by whoever keeps the cache keys
// (the frame systems, a tool's frame loop). One per view.
struct Convergence {
    std::array<std::uint64_t, pass_count> settled_key{}; // the row's key without its history
    std::array<std::uint64_t, pass_count> reset_key{};   // the same without its history_keeps reads
    std::array<std::uint16_t, pass_count> frames{};      // frames run since its key changed
    std::array<std::uint16_t, pass_count> age{};         // frames of history (since reset_key changed)
    std::uint32_t epoch = 0; // hashed into the converging rows' keys: restart() reruns them
    // After a frame ran: counts one more frame for each converging row in `ran`. (Not
    // calling it holds the rows where they are: their keys stay, a still scene shows the
    // same bounce; the HUD's bounce stepper, GiConfig::converge.)
    void advance(PassSet ran);
    // Forget everything (a failed frame: every row starts afresh).
    void reset() { *this = {}; }
    // Start every converging row afresh next frame, rerunning it (and what reads it) even
    // where its inputs did not change: the first bounce again.
    void restart() {
        const std::uint32_t next = epoch + 1;
        *this = {};
        epoch = next;
    }
};

// Every pass's cache key (0 for passes not planned): a hash of the window, the inputs the
// row lists, the values of the settings it lists, the textures it writes, the keys of the
// planned rows that last wrote each texture it reads, and the own keys of later planned
// rows that overwrite its outputs in place (so that turning such a row on or off, or
// changing it, reruns the producer). A pass whose key is unchanged keeps last frame's
// outputs. With `convergence`, a converging row whose key without history changed starts
// afresh, plan.history is set for every converging row (its age: frames since it started
// afresh), and its key includes min(frames since its key changed, converge_frames - 1): it
// changes every frame until the row has converged. A change only in a history_keeps read
// restarts that count but not the history.
// Without it, converging rows have history 0 (one frame: tools' single frames).
std::array<std::uint64_t, pass_count> derive_keys(const FrameInputs& in, PassPlan& plan, const InputKeys& inputs,
                                                  Convergence* convergence = nullptr);
// The same for the rows of `m` (a method built in code: tests).
std::array<std::uint64_t, pass_count> derive_keys(const Method& m, const FrameInputs& in, PassPlan& plan,
                                                  const InputKeys& inputs, Convergence* convergence = nullptr);

// Runs the planned rows that are in `subset` on the C++ reference, in pipeline order;
// `timed` (optional) is called with each pass's start and end (now_ns()).
using PassTimer = void (*)(void* user, Pass pass, std::int64_t start_ns, std::int64_t end_ns);
void execute_reference(const FrameInputs& in, const PassPlan& plan, PassSet subset, const RefOptions& options,
                       ReferenceStore& store, PassTimer timed = nullptr, void* user = nullptr);
// Releases what the planned rows no longer write (as the Vulkan backend does).
void release_unwritten(const FrameInputs& in, const PassPlan& plan, ReferenceStore& store);

} // namespace lantern::gi
