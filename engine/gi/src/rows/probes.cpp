// The live light probes' row (probes.hpp): after the indirect light, before the mixed and
// baked lights (a bake's probes hold those). Its texture, settings and inputs, its Vulkan
// recorder and its C++ reference.
#include "rows/rows.hpp"

#include "lantern/gi/gather.hpp"
#include "lantern/gi/probes.hpp"
#include "lantern/gi/radiosity.hpp"

#include <cstdint>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

// ProbeParams of gi_probes.comp.glsl, field by field.
struct ProbeParams {
    std::int32_t origin_x = 0, origin_z = 0, offset = 0, tiles = 0, window = 0, first = 0, rays = 0;
    float dtheta = 0.0f;
};

Tex direct_face(int f) { return Tex(int(Tex::wall_direct_px) + f); }
Tex indirect_face(int f) { return Tex(int(Tex::wall_indirect_px) + f); }

struct ProbeState : vk::PassState {
    UploadedArray directions, materials;
};

void record_probes(PassRecorder& r) {
    const FrameInputs& in = r.in;
    const ProbeGrid g = probe_grid(in);
    if (g.count.x == 0 || g.count.y == 0) return;
    ProbeState& s = r.state<ProbeState>();
    if (!s.directions.buffer)
        upload_array(r, s.directions, std::span<const glm::ivec2>(radiosity_directions()), VK_FORMAT_R32G32_SINT,
                     "probe directions");
    const std::vector<GpuMaterial> table = material_table(in);
    upload_array(r, s.materials, std::span<const GpuMaterial>(table), VK_FORMAT_R32G32B32A32_SFLOAT, "probe materials");
    r.cmd.barrier_transfer_to_compute();
    const std::uint32_t faces = computed_faces(in.settings);
    // Faces not computed are bound to a computed one's texture and never read.
    Tex first_face = Tex::wall_direct_px;
    for (int face = 3; face >= 0; --face)
        if (computes_face(faces, face)) first_face = direct_face(face);
    const bool indirect = r.has(indirect_face(int(first_face) - int(Tex::wall_direct_px)));
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls());
    for (int face = 0; face < 4; ++face) {
        const Tex d = computes_face(faces, face) ? direct_face(face) : first_face;
        writes.uniform_texel_buffer(std::uint32_t(1 + face), r.view(d));
        const Tex i = indirect ? indirect_face(int(d) - int(Tex::wall_direct_px)) : d;
        writes.uniform_texel_buffer(std::uint32_t(5 + face), r.view(i));
    }
    writes.uniform_texel_buffer(9, s.directions.view)
        .uniform_texel_buffer(10, s.materials.view)
        .storage_buffer(11, r.buffer(Tex::probes));
    // One probe an invocation, 32 a workgroup: with the renderer's blocks of 4 x 4 texels and
    // groups of 8 x 8 blocks, a window's few hundred probes made one or two workgroups, one
    // core's work (lavapipe runs a workgroup on one thread): in the game at 32 rays 2.4 ms p50
    // that way, 1.5 ms this way (docs/baked.md, "Live probes").
    constexpr std::uint32_t group_x = 8, group_y = 4;
    r.cmd.bind(r.pipeline<ProbeParams>("gi_probes.comp", {.proxies = false, .block_h = 1, .group_x = group_x,
                                                          .group_y = group_y, .features = indirect ? 1u : 0u,
                                                          .faces = faces}));
    r.cmd.push_descriptors(writes);
    const GatherFrame f = gather_frame(in);
    auto p = r.params<ProbeParams>(g.count.x, g.count.y);
    p.size.z = r.pitch(Tex::probes);
    const glm::ivec2 first = g.first_tile - f.origin_tile; // 0 or 1 each
    const PackedGatherFrame packed = pack(f);
    p.pass = {.origin_x = packed.origin_x,
              .origin_z = packed.origin_z,
              .offset = packed.offset,
              .tiles = packed.tiles,
              .window = packed.window,
              .first = first.x | (first.y << 16),
              .rays = in.settings.probe_rays,
              .dtheta = probe_dtheta(in.settings.probe_rays)};
    r.cmd.push_constants(p);
    r.cmd.dispatch((std::uint32_t(g.count.x) + group_x - 1) / group_x, (std::uint32_t(g.count.y) + group_y - 1) / group_y);
    r.cmd.barrier_compute_to_compute();
}

void reference_probes_row(ReferenceContext& c) {
    FaceTextures direct{}, indirect{};
    for (int face = 0; face < 4; ++face) {
        direct[std::size_t(face)] = c.store.find(direct_face(face));
        indirect[std::size_t(face)] = c.store.find(indirect_face(face));
    }
    c.store.put(Tex::probes, reference_probes(c.in, direct, indirect));
}

const char* probes_not_needed(const FrameInputs& in, bool, bool walls_in_window) {
    if (in.settings.probe_rays == 0) return "gi.probe_rays is 0";
    if (!in.settings.wall_lighting) return "wall lighting off";
    if (computed_faces(in.settings) == 0) return "no wall face computed";
    return walls_in_window ? nullptr : "no walls in the GI window";
}

constexpr Tex probes_reads[] = {Tex::wall_direct_px,   Tex::wall_direct_nx,   Tex::wall_direct_pz,   Tex::wall_direct_nz,
                                Tex::wall_indirect_px, Tex::wall_indirect_nx, Tex::wall_indirect_pz, Tex::wall_indirect_nz};
constexpr Tex probes_writes[] = {Tex::probes};
constexpr std::string_view probes_settings[] = {"probe_rays",    "wall_albedo",   "albedo_boost",  "wall_lighting",
                                                "wall_faces.px", "wall_faces.nx", "wall_faces.pz", "wall_faces.nz"};

} // namespace

constinit const PassRow probes{
    .pass = Pass::probes,
    .name = "probes",
    .reads = probes_reads,
    .writes = probes_writes,
    .settings = probes_settings,
    .inputs = input_walls | input_walls_in_window,
    .not_needed = probes_not_needed,
    .record = record_probes,
    .reference = reference_probes_row,
};

} // namespace lantern::gi::rows
