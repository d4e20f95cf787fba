// Rows of the indirect-light passes of seed 000's heat method: emission, heat transfer
// (seed, tap masks, rounds, upsample), blur, wall-face indirect. Each row: its textures,
// settings and inputs, its Vulkan recorder and its C++ reference.
#include "rows/rows.hpp"

#include "lantern/gi/reference_indirect.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>
#include <utility>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

// The parameters of each shader (GI_PASS_PARAMS, mirrored field by field; checked against
// the shader when its pipeline is created).
struct EmissionParams {
    float strength = 0;
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0, pad5 = 0, pad6 = 0;
};
struct HeatSeedParams {
    std::int32_t full_width = 0, full_height = 0, full_pitch = 0, scale = 0, pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0;
};
struct HeatMaskParams {
    float texels_per_unit = 0, distance = 0, segment_radius = 0;
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0;
};
struct HeatRoundParams {
    float texels_per_unit = 0, distance = 0, rate = 0, range_boost = 0, intensity_multiplier = 0;
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0;
};
struct UpsampleParams {
    std::int32_t heat_width = 0, heat_height = 0, heat_pitch = 0;
    float texels_per_unit = 0;
    std::int32_t scale = 0, pad0 = 0, pad1 = 0, pad2 = 0;
};
struct BlurParams {
    std::int32_t axis_x = 0, axis_y = 0, pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0, pad5 = 0;
};

// ---- emission

void record_emission(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    r.cmd.bind(r.pipeline<EmissionParams>("gi_emission.comp", {.proxies = false}));
    r.cmd.push_descriptors(
        gpu::DescriptorWrites().uniform_texel_buffer(0, r.view(Tex::direct)).storage_buffer(1, r.buffer(Tex::emission)));
    auto p = r.params<EmissionParams>(w.width, w.height);
    p.pass.strength = r.in.settings.emission_strength;
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_emission_row(ReferenceContext& c) {
    c.store.put(Tex::emission, reference_emission(c.in, c.store.at(Tex::direct), c.options));
}

// ---- heat transfer: heat_rounds + 2 iterations (seed and tap masks, the rounds, upsample)

int heat_iterations(const FrameInputs& in) { return in.settings.heat_rounds + 2; }

// The heat texture round `round` (1-based) reads; after the last round, the result.
Tex heat_source(int round) { return round % 2 == 1 ? Tex::heat_a : Tex::heat_b; }
Tex heat_result(int rounds) { return rounds % 2 == 1 ? Tex::heat_b : Tex::heat_a; }

// The tap masks depend on the window, the walls and the heat grid's settings, not on the
// light: the row keeps them from its last run while those stay (a torch's flicker and the
// player's lantern rerun the heat every frame; the masks' segment checks were a fifth of it).
struct HeatState : vk::PassState {
    std::uint64_t mask_context = 0; // what the masks were computed for; 0: nothing known
};

std::uint64_t heat_mask_context(PassRecorder& r, const HeatGrid& g, float distance, float segment_radius) {
    Hasher h;
    add_window_and_walls(h, r.in);
    h.add(g.width).add(g.height).add(g.scale).add(g.texels_per_unit).add(distance).add(segment_radius);
    h.add(r.in.settings.segment_check).add(r.serial(Tex::heat_mask));
    h.add(r.block_h()).add(r.group_x()).add(r.group_y());
    const std::uint64_t v = h.value();
    return v ? v : 1;
}

void record_heat(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    const scene::GiSettings& s = r.in.settings;
    const HeatGrid g = heat_grid(w, s.heat_scale);
    const float distance = s.diffusion_distance * g.texels_per_unit;
    const float segment_radius = s.diffusion_distance * 2.0f + 2.0f;
    const int rounds = s.heat_rounds;
    if (r.iteration == 0) {
        // Seed.
        r.cmd.bind(r.pipeline<HeatSeedParams>("gi_heat_seed.comp", {.proxies = false}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.view(Tex::emission))
                                   .uniform_texel_buffer(1, r.view(Tex::shadow))
                                   .storage_buffer(2, r.buffer(Tex::heat_a)));
        auto seed = r.params<HeatSeedParams>(g.width, g.height);
        seed.pass = {.full_width = w.width, .full_height = w.height, .full_pitch = r.pitch(Tex::emission),
                     .scale = g.scale};
        r.cmd.push_constants(seed);
        r.dispatch(g.width, g.height);
        r.cmd.barrier_compute_to_compute();
        // Tap masks: which taps each heat texel may use (air, segment clear), kept while the
        // window, the walls and the settings stay (RendererOptions::dirty_bins).
        HeatState& state = r.state<HeatState>();
        const std::uint64_t context = heat_mask_context(r, g, distance, segment_radius);
        const std::uint64_t mask_groups = r.dispatch_groups(g.width, g.height);
        const bool kept = r.dirty_bins() && state.mask_context == context;
        r.count_workgroups(mask_groups, kept ? 0 : mask_groups);
        if (kept) return;
        state.mask_context = context;
        r.cmd.bind(r.pipeline<HeatMaskParams>("gi_heat_mask.comp", {.proxies = false, .segment_check = s.segment_check}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.walls())
                                   .uniform_buffer(1, r.proxies())
                                   .storage_buffer(2, r.buffer(Tex::heat_mask)));
        auto mask = r.params<HeatMaskParams>(g.width, g.height);
        mask.pass = {.texels_per_unit = g.texels_per_unit, .distance = distance,
                     .segment_radius = segment_radius};
        r.cmd.push_constants(mask);
        r.dispatch(g.width, g.height);
        r.cmd.barrier_compute_to_compute();
    } else if (r.iteration <= rounds) {
        // One round, ping-pong.
        const Tex src = heat_source(r.iteration), dst = src == Tex::heat_a ? Tex::heat_b : Tex::heat_a;
        // FEATURES bit 0: the three rings' 24 taps.
        const std::uint32_t rings = heat_tap_rings(distance) ? 1u : 0u;
        r.cmd.bind(r.pipeline<HeatRoundParams>("gi_heat.comp",
                                               {.proxies = false, .per_channel = s.per_channel, .features = rings}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.view_u32(Tex::heat_mask))
                                   .uniform_texel_buffer(1, r.view(src))
                                   .storage_buffer(2, r.buffer(dst)));
        auto round = r.params<HeatRoundParams>(g.width, g.height);
        round.pass = {.texels_per_unit = g.texels_per_unit, .distance = distance, .rate = s.diffusion_rate,
                      .range_boost = s.range_boost, .intensity_multiplier = s.intensity_multiplier};
        r.cmd.push_constants(round);
        r.dispatch(g.width, g.height);
        r.cmd.barrier_compute_to_compute();
    } else {
        record_upsample(r, heat_result(rounds), g, true);
    }
}

void reference_heat_row(ReferenceContext& c) {
    const int rounds = c.in.settings.heat_rounds;
    if (c.iteration == 0) {
        c.store.put(Tex::heat_a,
                    reference_heat_seed(c.in, c.store.at(Tex::emission), c.store.at(Tex::shadow), c.options));
    } else if (c.iteration <= rounds) {
        const Tex src = heat_source(c.iteration), dst = src == Tex::heat_a ? Tex::heat_b : Tex::heat_a;
        c.store.put(dst, reference_heat_round(c.in, c.store.at(src), c.options));
    } else {
        c.store.put(Tex::indirect, reference_heat_upsample(c.in, c.store.at(heat_result(rounds)), c.options));
    }
}

// ---- blur (in place on the indirect texture)

void record_blur(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    auto blur_pass = [&](Tex src, Tex dst, glm::ivec2 axis) {
        // The axis is the shader's FEATURES bit 0 (a specialisation constant), not a branch.
        r.cmd.bind(r.pipeline<BlurParams>("gi_blur.comp", {.proxies = false, .features = axis.y != 0 ? 1u : 0u}));
        r.cmd.push_descriptors(gpu::DescriptorWrites()
                                   .uniform_texel_buffer(0, r.view(Tex::conduction))
                                   .uniform_texel_buffer(1, r.view(src))
                                   .storage_buffer(2, r.buffer(dst)));
        auto p = r.params<BlurParams>(w.width, w.height);
        p.pass = {.axis_x = axis.x, .axis_y = axis.y};
        r.cmd.push_constants(p);
        r.dispatch(w.width, w.height);
        r.cmd.barrier_compute_to_compute();
    };
    blur_pass(Tex::indirect, Tex::blur_temp, {1, 0});
    blur_pass(Tex::blur_temp, Tex::indirect, {0, 1});
}

void reference_blur_row(ReferenceContext& c) {
    c.store.put(Tex::indirect, reference_blur(c.in, c.store.at(Tex::indirect), c.store.at(Tex::conduction), c.options));
}

// ---- wall-face indirect

// gi_wall_indirect.comp's parameters: with a list of blocks, its length.
struct WallIndirectParams {
    std::int32_t blocks = 0;
    std::int32_t unused1 = 0, unused2 = 0, unused3 = 0, unused4 = 0, unused5 = 0, unused6 = 0, unused7 = 0;
};

// Off wall texels the pass writes zeros, and the baked row adds zeros there, so once the
// whole window is written the blocks with no wall texel keep their zeros while the window,
// the walls and the textures stay and the row stays in every frame's plan (out of it, other
// rows may write the faces: the gather's alpha is 1 off walls). Then only the blocks holding
// a wall texel (rows::wall_blocks) are computed again.
struct WallIndirectState : vk::PassState {
    std::uint64_t zeros_key = 0; // the window, walls and textures of the last run (0: none)
    std::uint64_t plan = 0;      // the plan of the last run (PassRecorder::plan_serial)
    UploadedArray blocks;        // the listed blocks, or a stand-in
};

void record_wall_indirect(PassRecorder& r) {
    WallIndirectState& s = r.state<WallIndirectState>();
    const GiWindow& w = r.in.window;
    const std::uint32_t faces = computed_faces(r.in.settings);
    // FEATURES bit 0: the block's tile looked up once; bit 1: the listed blocks alone.
    const std::uint32_t block_tile = r.blocks_in_one_tile() ? 1u : 0u;
    Hasher key;
    add_window_and_walls(key, r.in).add(std::uint32_t(r.in.settings.method)).add(faces).add(r.block_h());
    for (int f = 0; f < 4; ++f) {
        const Tex t = Tex(int(Tex::wall_indirect_px) + f);
        if (computes_face(faces, f)) key.add(r.serial(t)).add(r.pitch(t)).add(r.buffer(t).size());
    }
    const std::uint64_t zeros_key = key.value() | 1;
    std::optional<std::vector<std::uint32_t>> blocks;
    if (r.dirty_bins() && s.zeros_key == zeros_key && r.planned_since(s.plan))
        blocks = wall_blocks(r.in, int(r.block_h()), 65535ull * r.group_x() * r.group_y());
    s.zeros_key = zeros_key;
    s.plan = r.plan_serial();
    upload_list(r, s.blocks, blocks ? &*blocks : nullptr, "gi wall indirect blocks");
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls()).uniform_buffer(1, r.proxies()).uniform_texel_buffer(2, r.view(Tex::indirect));
    // A face not computed is bound to the first computed face's buffer and never written.
    Tex first = Tex::wall_indirect_px;
    for (int f = 3; f >= 0; --f)
        if (computes_face(faces, f)) first = Tex(int(Tex::wall_indirect_px) + f);
    for (int f = 0; f < 4; ++f) {
        const Tex t = Tex(int(Tex::wall_indirect_px) + f);
        writes.storage_buffer(std::uint32_t(3 + f), r.buffer(computes_face(faces, f) ? t : first));
    }
    writes.storage_buffer(7, s.blocks.buffer);
    const std::uint32_t features = block_tile | (blocks ? 2u : 0u);
    r.cmd.bind(r.pipeline<WallIndirectParams>("gi_wall_indirect.comp", {.proxies = false, .features = features, .faces = faces}));
    // The other variants, before a frame needs them: a window snapped to texels may move off
    // the blocks' alignment (or onto it), and the first frame after a step lists its blocks.
    for (std::uint32_t v = 0; v < 4; ++v)
        if (v != features && ((v & 1u) == block_tile || r.in.settings.window_snap == scene::WindowSnap::texel))
            r.prefetch_pipeline<WallIndirectParams>("gi_wall_indirect.comp", {.proxies = false, .features = v, .faces = faces});
    r.cmd.push_descriptors(writes);
    auto params = r.params<WallIndirectParams>(w.width, w.height);
    params.pass.blocks = blocks ? std::int32_t(blocks->size()) : 0;
    r.cmd.push_constants(params);
    const std::uint64_t all = r.dispatch_groups(w.width, w.height);
    if (!blocks) {
        r.dispatch(w.width, w.height);
        r.count_workgroups(all, all);
    } else {
        r.count_workgroups(all, dispatch_listed_blocks(r, blocks->size()));
    }
    r.cmd.barrier_compute_to_compute();
}

void reference_wall_indirect_row(ReferenceContext& c) {
    auto faces = reference_wall_indirect(c.in, c.store.at(Tex::indirect), c.options);
    for (int f = 0; f < 4; ++f)
        if (faces[std::size_t(f)].width > 0) c.store.put(Tex(int(Tex::wall_indirect_px) + f), std::move(faces[std::size_t(f)]));
}

TexSet wall_indirect_writes(const FrameInputs& in) {
    TexSet set;
    const std::uint32_t faces = computed_faces(in.settings);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) set.add(Tex(int(Tex::wall_indirect_px) + f));
    return set;
}

const char* blur_not_needed(const FrameInputs& in, bool, bool) { return in.settings.blur ? nullptr : "blur disabled"; }
const char* wall_indirect_not_needed(const FrameInputs& in, bool, bool walls_in_window) {
    if (!in.settings.wall_lighting) return "wall lighting off";
    if (computed_faces(in.settings) == 0) return "no wall face computed";
    return walls_in_window ? nullptr : "no walls in the GI window";
}

constexpr Tex emission_reads[] = {Tex::direct};
constexpr Tex emission_writes[] = {Tex::emission};
constexpr std::string_view emission_settings[] = {"emission_strength"};
constexpr Tex heat_reads[] = {Tex::emission, Tex::shadow};
constexpr Tex heat_writes[] = {Tex::heat_a, Tex::heat_b, Tex::heat_mask, Tex::indirect};
constexpr std::string_view heat_settings[] = {"heat_rounds",    "heat_scale",           "diffusion_rate",
                                              "diffusion_distance", "range_boost", "intensity_multiplier",
                                              "per_channel",    "segment_check"};
constexpr Tex blur_reads[] = {Tex::indirect, Tex::conduction};
constexpr Tex blur_writes[] = {Tex::blur_temp, Tex::indirect};
constexpr std::string_view blur_settings[] = {"blur"};
constexpr Tex wall_indirect_reads[] = {Tex::indirect};
constexpr std::string_view wall_indirect_settings[] = {"wall_lighting", "wall_faces.px", "wall_faces.nx",
                                                       "wall_faces.pz", "wall_faces.nz"};

} // namespace

Hasher& add_window_and_walls(Hasher& h, const FrameInputs& in) {
    const WallView& walls = in.walls;
    h.add(hash_window(in.window)).add(in.window.width).add(in.window.height).add(in.window.resolution);
    h.add(walls.width).add(walls.height).add(walls.origin.x).add(walls.origin.y).add(walls.phase.x).add(walls.phase.y);
    return h.add_bytes(walls.cells, std::size_t(walls.width) * std::size_t(walls.height));
}

void record_upsample(PassRecorder& r, Tex src, const HeatGrid& g, bool heat_mask) {
    const GiWindow& w = r.in.window;
    r.cmd.bind(r.pipeline<UpsampleParams>("gi_upsample.comp", {.proxies = false, .features = heat_mask ? 1u : 0u}));
    r.cmd.push_descriptors(gpu::DescriptorWrites()
                               .uniform_texel_buffer(0, r.walls())
                               .uniform_buffer(1, r.proxies())
                               .uniform_texel_buffer(2, r.view(src))
                               .storage_buffer(3, r.buffer(Tex::indirect))
                               .uniform_texel_buffer(4, heat_mask ? r.view_u32(Tex::heat_mask) : r.walls()));
    auto up = r.params<UpsampleParams>(w.width, w.height);
    up.pass = {.heat_width = g.width, .heat_height = g.height, .heat_pitch = r.pitch(src),
               .texels_per_unit = g.texels_per_unit, .scale = g.scale};
    r.cmd.push_constants(up);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

constinit const PassRow emission{
    .pass = Pass::emission,
    .name = "emission",
    .reads = emission_reads,
    .writes = emission_writes,
    .settings = emission_settings,
    .record = record_emission,
    .reference = reference_emission_row,
};

constinit const PassRow heat{
    .pass = Pass::heat,
    .name = "heat",
    .reads = heat_reads,
    .writes = heat_writes,
    .settings = heat_settings,
    .inputs = input_walls,
    .iterations = heat_iterations,
    .record = record_heat,
    .reference = reference_heat_row,
};

constinit const PassRow blur{
    .pass = Pass::blur,
    .name = "blur",
    .reads = blur_reads,
    .writes = blur_writes,
    .settings = blur_settings,
    .inputs = input_walls,
    .not_needed = blur_not_needed,
    .record = record_blur,
    .reference = reference_blur_row,
};

constinit const PassRow wall_indirect{
    .pass = Pass::wall_indirect,
    .name = "wall_indirect",
    .reads = wall_indirect_reads,
    .writes_for = wall_indirect_writes,
    .settings = wall_indirect_settings,
    .inputs = input_walls | input_walls_in_window,
    .not_needed = wall_indirect_not_needed,
    .record = record_wall_indirect,
    .reference = reference_wall_indirect_row,
};

} // namespace lantern::gi::rows
