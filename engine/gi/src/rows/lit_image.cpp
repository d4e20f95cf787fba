// The lit-image row: the GI textures shaded and tone-mapped into an sRGB image (tools and
// tests; the game shades in its raster pass instead, from the same shading library).
#include "rows/rows.hpp"

#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <cstdint>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

constexpr Tex lit_reads[] = {Tex::direct,           Tex::indirect,         Tex::ao,
                             Tex::shadow,           Tex::wall_direct_px,   Tex::wall_direct_nx,
                             Tex::wall_direct_pz,   Tex::wall_direct_nz,   Tex::wall_indirect_px,
                             Tex::wall_indirect_nx, Tex::wall_indirect_pz, Tex::wall_indirect_nz,
                             Tex::wall_upper_px,    Tex::wall_upper_nx,    Tex::wall_upper_pz,
                             Tex::wall_upper_nz};
constexpr Tex lit_writes[] = {Tex::lit};
constexpr std::string_view lit_settings[] = {"tone_map",      "white_point",   "directional_angle_scale",
                                             "wall_lighting", "wall_faces.px", "wall_faces.nx",
                                             "wall_faces.pz", "wall_faces.nz", "ao.walls"};

// The shader's parameters (GI_PASS_PARAMS LitParams), field by field.
struct LitParams {
    float wall_height = 0;
    std::uint32_t present = 0; // bit i: lit_reads[i] is bound
    std::int32_t tone_map = 0;
    float white_point = 0, angle_scale = 0;
    std::int32_t pad_f = 0; // (the faces computed: PipelineSpec::faces)
    float wall_lighting = 1, ao_walls = 0;
};

void record_lit(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    // Absent textures are bound as the direct texture (any valid view) and flagged absent.
    std::uint32_t present = 0;
    auto view_or = [&](Tex t, std::uint32_t bit) -> const gpu::BufferView& {
        if (r.has(t)) {
            present |= 1u << bit;
            return r.view(t);
        }
        return r.view(Tex::direct);
    };
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls()).uniform_buffer(1, r.proxies()).uniform_buffer(2, r.suns());
    for (std::uint32_t i = 0; i < 12; ++i) writes.uniform_texel_buffer(3 + i, view_or(lit_reads[i], i));
    writes.storage_buffer(15, r.buffer(Tex::lit));
    for (std::uint32_t i = 12; i < 16; ++i) writes.uniform_texel_buffer(4 + i, view_or(lit_reads[i], i));
    r.cmd.bind(r.pipeline<LitParams>("gi_lit.comp", {.proxies = false, .walls = r.plan.has_walls_in_window,
                                                .faces = computed_faces(r.in.settings)}));
    r.cmd.push_descriptors(writes);
    auto p = r.params<LitParams>(w.width, w.height);
    const scene::GiSettings& s = r.in.settings;
    p.pass = {.wall_height = r.in.wall_height, .present = present, .tone_map = std::int32_t(s.tone_map),
              .white_point = s.white_point, .angle_scale = s.directional_angle_scale,
              .wall_lighting = s.wall_lighting ? 1.0f : 0.0f,
              .ao_walls = s.ao.walls ? 1.0f : 0.0f};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_lit_row(ReferenceContext& c) { c.store.lit = reference_lit_image(c.store.shading_inputs(c.in), c.options); }

const char* lit_not_needed(const FrameInputs&, bool lit_image, bool) {
    return lit_image ? nullptr : "no lit image requested";
}

} // namespace

constinit const PassRow lit{
    .pass = Pass::lit,
    .name = "lit",
    .reads = lit_reads,
    .writes = lit_writes,
    .settings = lit_settings,
    .inputs = input_walls | input_suns | input_wall_height | input_walls_in_window,
    .not_needed = lit_not_needed,
    .record = record_lit,
    .reference = reference_lit_row,
};

} // namespace lantern::gi::rows
