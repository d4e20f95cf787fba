// Rows of seed 003's radiosity method (radiosity.hpp): the distance field (jump flood) and
// the radiosity (light image, raymarch with accumulation, upsample). Each row: its
// textures, settings and inputs, its Vulkan recorder and its C++ reference.
#include "rows/rows.hpp"

#include "lantern/gi/blue_noise.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <cstdint>
#include <optional>
#include <utility>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

// The parameters of each shader (GI_PASS_PARAMS, mirrored field by field).
struct JumpFloodParams {
    float texels_per_unit = 0;
    std::int32_t offset = 0, pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0, pad5 = 0;
};
struct RadiosityLightParams {
    std::int32_t full_width = 0, full_height = 0, full_pitch = 0, scale = 0;
    float texels_per_unit = 0, feedback = 0;
    std::int32_t pad0 = 0, pad1 = 0;
};
struct RadiosityParams {
    std::int32_t rays = 0, steps = 0, epsilon_steps = 0, shift = 0;
    std::int32_t noise_origin = -1; // x | y << 8, -1: no per-texel noise
    float accumulate_weight = 1, own_weight = 0;
    std::int32_t pad0 = 0;
};

// ---- distance field: seed, the jump-flood passes, finish

int distance_iterations(const FrameInputs& in) {
    const HeatGrid g = radiosity_grid(in);
    return int(jump_flood_offsets({g.width, g.height}).size()) + 2;
}

// The jump-flood texture pass `pass` (0: the seed) writes.
Tex jfa_target(int pass) {
    return pass % 2 == 0 ? Tex::jfa_a : Tex::jfa_b;
}

void record_distance_field(PassRecorder& r) {
    const HeatGrid g = radiosity_grid(r.in);
    const std::vector<int> offsets = jump_flood_offsets({g.width, g.height});
    const int last = int(offsets.size()) + 1;
    const std::uint32_t mode = r.iteration == 0 ? 0u : r.iteration < last ? 1u : 2u;
    const Tex src = jfa_target(std::max(r.iteration - 1, 0));
    LANTERN_ASSERT(mode != 2 || src == jump_flood_result(r.in), "jump_flood_result disagrees with the row");
    const Tex dst = mode == 2 ? Tex::distance_steps : jfa_target(r.iteration);
    r.cmd.bind(
        r.pipeline<JumpFloodParams>("gi_jump_flood.comp", {.proxies = false, .features = mode}));
    r.cmd.push_descriptors(gpu::DescriptorWrites()
                               .uniform_texel_buffer(0, r.walls())
                               .uniform_buffer(1, r.proxies())
                               .uniform_texel_buffer(2, r.view_u32(src))
                               .storage_buffer(3, r.buffer(dst))
                               .storage_buffer(4, r.buffer(Tex::distance_field)));
    auto p = r.params<JumpFloodParams>(g.width, g.height);
    p.pass.texels_per_unit = g.texels_per_unit;
    p.pass.offset = mode == 1 ? offsets[std::size_t(r.iteration - 1)] : 0;
    r.cmd.push_constants(p);
    r.dispatch(g.width, g.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_distance_field_row(ReferenceContext& c) {
    const HeatGrid g = radiosity_grid(c.in);
    const std::vector<int> offsets = jump_flood_offsets({g.width, g.height});
    const int last = int(offsets.size()) + 1;
    if (c.iteration == 0) {
        c.store.put(Tex::jfa_a, reference_jump_flood_seed(c.in));
    } else if (c.iteration < last) {
        const Tex src = jfa_target(c.iteration - 1);
        c.store.put(jfa_target(c.iteration),
                    reference_jump_flood_pass(c.store.at(src),
                                              offsets[std::size_t(c.iteration - 1)], c.options));
    } else {
        DistanceTextures d =
            reference_distance_field(c.store.at(jfa_target(c.iteration - 1)), c.options);
        c.store.put(Tex::distance_field, std::move(d.field));
        c.store.put(Tex::distance_steps, std::move(d.steps));
    }
}

// ---- radiosity: light image, raymarch + accumulation, upsample

// Last frame's radiosity feeds this frame's light only once there is a last frame.
float feedback_of(const FrameInputs& in, int history) {
    return history > 0 ? in.settings.radiosity.feedback : 0.0f;
}

// The ray directions and the blue noise, uploaded once per renderer.
struct RadiosityState : vk::PassState {
    UploadedArray directions, noise;
};

void record_radiosity(PassRecorder& r) {
    const HeatGrid g = radiosity_grid(r.in);
    if (r.iteration == 0) {
        const float feedback = feedback_of(r.in, r.history);
        r.cmd.bind(r.pipeline<RadiosityLightParams>("gi_radiosity_light.comp", {.proxies = false}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.walls())
                                   .uniform_buffer(1, r.proxies())
                                   .uniform_texel_buffer(2, r.view(Tex::emission))
                                   .uniform_texel_buffer(3, r.view(Tex::radiosity))
                                   .storage_buffer(4, r.buffer(Tex::radiosity_light)));
        auto p = r.params<RadiosityLightParams>(g.width, g.height);
        p.pass = {.full_width = r.in.window.width,
                  .full_height = r.in.window.height,
                  .full_pitch = r.pitch(Tex::emission),
                  .scale = g.scale,
                  .texels_per_unit = g.texels_per_unit,
                  .feedback = feedback};
        r.cmd.push_constants(p);
        r.dispatch(g.width, g.height);
        r.cmd.barrier_compute_to_compute();
    } else if (r.iteration == 1) {
        RadiosityState& s = r.state<RadiosityState>();
        if (!s.directions.buffer) {
            const std::vector<std::uint16_t>& ranks = blue_noise_ranks();
            const std::vector<std::uint32_t> noise(ranks.begin(), ranks.end());
            upload_array(r, s.directions, std::span<const glm::ivec2>(radiosity_directions()),
                         VK_FORMAT_R32G32_SINT, "radiosity directions");
            upload_array(r, s.noise, std::span<const std::uint32_t>(noise), VK_FORMAT_R32_UINT, "blue noise");
            r.cmd.barrier_transfer_to_compute();
        }
        const RadiosityMarch m = radiosity_march_params(r.in, r.history);
        r.cmd.bind(r.pipeline<RadiosityParams>("gi_radiosity.comp", {.proxies = false}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.view(Tex::radiosity_light))
                                   .uniform_texel_buffer(1, r.view_u32(Tex::distance_steps))
                                   .uniform_texel_buffer(2, s.directions.view)
                                   .uniform_texel_buffer(3, s.noise.view)
                                   .storage_buffer(4, r.buffer(Tex::radiosity)));
        auto p = r.params<RadiosityParams>(g.width, g.height);
        p.pass = {.rays = m.rays,
                  .steps = m.steps,
                  .epsilon_steps = m.epsilon_steps,
                  .shift = m.shift,
                  .noise_origin = m.noise ? m.noise_origin.x | (m.noise_origin.y << 8) : -1,
                  .accumulate_weight = m.accumulate_weight,
                  .own_weight = m.own_weight};
        r.cmd.push_constants(p);
        r.dispatch(g.width, g.height);
        r.cmd.barrier_compute_to_compute();
    } else {
        record_upsample(r, Tex::radiosity, g);
    }
}

void reference_radiosity_row(ReferenceContext& c) {
    const HeatGrid g = radiosity_grid(c.in);
    if (c.iteration == 0) {
        const float feedback = feedback_of(c.in, c.history);
        const Texture* previous = feedback > 0.0f ? c.store.find(Tex::radiosity) : nullptr;
        c.store.put(Tex::radiosity_light, reference_radiosity_light(c.in, c.store.at(Tex::emission),
                                                                    previous, feedback, c.options));
    } else if (c.iteration == 1) {
        const RadiosityMarch m = radiosity_march_params(c.in, c.history);
        // Last frame's radiosity is accumulated into in place: moved out of the store and back.
        std::optional<Texture>& previous = c.store.textures[std::size_t(Tex::radiosity)];
        Texture radiosity = previous && previous->width == g.width && previous->height == g.height
                                ? std::move(*previous)
                                : Texture("radiosity", TexFormat::rgba16f, g.width, g.height);
        reference_radiosity_march(c.store.at(Tex::radiosity_light), c.store.at(Tex::distance_steps),
                                  m, radiosity, c.options);
        c.store.put(Tex::radiosity, std::move(radiosity));
    } else {
        c.store.put(Tex::indirect,
                    reference_upsample(c.in, g, c.store.at(Tex::radiosity), c.options));
    }
}

int radiosity_iterations(const FrameInputs&) {
    return 3;
} // light image, march, upsample
int radiosity_frames(const FrameInputs& in) {
    return in.settings.radiosity.frames;
}

constexpr Tex distance_writes[] = {Tex::jfa_a, Tex::jfa_b, Tex::distance_field,
                                   Tex::distance_steps};
constexpr std::string_view distance_settings[] = {"radiosity.scale"};
constexpr Tex radiosity_reads[] = {Tex::emission, Tex::distance_steps, Tex::radiosity};
constexpr Tex radiosity_writes[] = {Tex::radiosity_light, Tex::radiosity, Tex::indirect};
constexpr Tex radiosity_keeps[] = {Tex::emission};
constexpr std::string_view radiosity_settings[] = {
    "radiosity.scale",    "radiosity.rays",       "radiosity.steps", "radiosity.epsilon",
    "radiosity.feedback", "radiosity.accumulate", "radiosity.noise", "radiosity.frames"};

} // namespace

constinit const PassRow distance_field{
    .pass = Pass::distance_field,
    .name = "distance_field",
    .writes = distance_writes,
    .settings = distance_settings,
    .inputs = input_walls,
    .iterations = distance_iterations,
    .record = record_distance_field,
    .reference = reference_distance_field_row,
};

constinit const PassRow radiosity{
    .pass = Pass::radiosity,
    .name = "radiosity",
    .reads = radiosity_reads,
    .writes = radiosity_writes,
    .settings = radiosity_settings,
    .inputs = input_walls,
    .iterations = radiosity_iterations,
    .converge_frames = radiosity_frames,
    .history_keeps = radiosity_keeps,
    .record = record_radiosity,
    .reference = reference_radiosity_row,
};

} // namespace lantern::gi::rows
