// The row of the gather method (gather.hpp): face bounces, the fill of the wall textures,
// the ground gather and its upsample. Its textures, settings and inputs, its Vulkan
// recorder and its C++ reference.
#include "rows/rows.hpp"

#include "lantern/gi/blue_noise.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/radiosity.hpp"

#include <cstdint>
#include <optional>
#include <utility>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

// GatherParams of gi_gather.comp.glsl, field by field.
struct GatherParams {
    std::int32_t origin_x = 0, origin_z = 0, offset = 0, tiles = 0, rays = 0, noise = 0, window = 0, pad = 0;
};

// Without lit faces (gi.wall_lighting off, no face computed) there is nothing to reflect: the
// row writes zero indirect light in one step.
bool has_sources(const FrameInputs& in) {
    return in.settings.wall_lighting && computed_faces(in.settings) != 0;
}

// Iterations: the face bounces, the fill, the ground, the upsample.
int gather_iterations(const FrameInputs& in) {
    return has_sources(in) ? in.settings.gather.bounces + 3 : 1;
}
int gather_frames(const FrameInputs& in) {
    return in.settings.gather.frames;
}

// The face bounce of iteration `it` counts from the first frame's first bounce.
int face_step(const FrameInputs& in, int history, int it) {
    return history * in.settings.gather.bounces + it;
}
// The face texture the last bounce of this frame wrote.
Tex final_faces(const FrameInputs& in, int history) {
    return gather_face_target(face_step(in, history, in.settings.gather.bounces - 1));
}

Tex direct_face(int f) {
    return Tex(int(Tex::wall_direct_px) + f);
}

struct GatherState : vk::PassState {
    UploadedArray directions, noise, faces, ground, materials;
    int face_rows = 0, ground_rows = 0;
};

// The face bounces and the ground gather run over lists of the texels that have work, not
// over the window: on lavapipe a lane without work still runs every loop once, masked. An
// entry is (x | y << 16, face); the list is padded with ~0 to whole rows of this width.
constexpr int list_width = 256; // gi_gather.comp.glsl LIST_WIDTH
int pad_rows(std::vector<glm::uvec2>& list) {
    const int rows = int((list.size() + list_width - 1) / list_width);
    list.resize(std::size_t(rows) * list_width, glm::uvec2(0xFFFFFFFFu, 0u));
    return rows;
}

// Exposed face texels of the window, with their face.
std::vector<glm::uvec2> face_list(const FrameInputs& in, const GatherFrame& f) {
    std::vector<glm::uvec2> list;
    for (int y = 0; y < in.window.height; ++y)
        for (int x = 0; x < in.window.width; ++x)
            for (int face = 0; face < 4; ++face)
                if (gather_face_texel(in, f, x, y, face))
                    list.push_back({std::uint32_t(x) | (std::uint32_t(y) << 16), std::uint32_t(face)});
    return list;
}

// Texels of the gather grid whose centre is in air (reference_gather_ground's test).
std::vector<glm::uvec2> ground_list(const FrameInputs& in, const GatherFrame& f, const HeatGrid& g) {
    std::vector<glm::uvec2> list;
    for (int j = 0; j < g.height; ++j)
        for (int i = 0; i < g.width; ++i)
            if (gather_ground_texel_in_air(in, f, g, i, j))
                list.push_back({std::uint32_t(i) | (std::uint32_t(j) << 16), 0u});
    return list;
}

void record_gather(PassRecorder& r) {
    const FrameInputs& in = r.in;
    const int bounces = in.settings.gather.bounces;
    const std::uint32_t faces = computed_faces(in.settings);
    const HeatGrid g = gather_grid(in);
    if (!has_sources(in)) {
        r.clear(Tex::gather_ground);
        r.clear(Tex::indirect);
        r.cmd.barrier_transfer_to_compute();
        return;
    }
    if (r.iteration == bounces + 2) {
        record_upsample(r, Tex::gather_ground, g);
        return;
    }
    GatherState& s = r.state<GatherState>();
    if (!s.directions.buffer) {
        const std::vector<std::uint16_t>& ranks = blue_noise_ranks();
        const std::vector<std::uint32_t> noise(ranks.begin(), ranks.end());
        upload_array(r, s.directions, std::span<const glm::ivec2>(radiosity_directions()), VK_FORMAT_R32G32_SINT,
                     "gather directions");
        upload_array(r, s.noise, std::span<const std::uint32_t>(noise), VK_FORMAT_R32_UINT, "gather blue noise");
        r.cmd.barrier_transfer_to_compute();
    }
    const GatherFrame f = gather_frame(in);
    if (r.iteration == 0) { // this frame's lists (the walls or window may have changed)
        std::vector<glm::uvec2> faces_now = face_list(in, f), ground_now = ground_list(in, f, g);
        s.face_rows = pad_rows(faces_now);
        s.ground_rows = pad_rows(ground_now);
        if (s.face_rows) upload_array(r, s.faces, std::span<const glm::uvec2>(faces_now), VK_FORMAT_R32G32_UINT, "gather face texels");
        if (s.ground_rows) upload_array(r, s.ground, std::span<const glm::uvec2>(ground_now), VK_FORMAT_R32G32_UINT, "gather ground texels");
        const std::vector<GpuMaterial> table = material_table(in);
        upload_array(r, s.materials, std::span<const GpuMaterial>(table), VK_FORMAT_R32G32B32A32_SFLOAT, "gather materials");
        r.cmd.barrier_transfer_to_compute();
    }
    int mode = 0;
    Tex source = final_faces(in, r.history), out0 = Tex::gather_ground;
    bool previous = true;
    if (r.iteration < bounces) {
        const int step = face_step(in, r.history, r.iteration);
        previous = step > 0;
        source = gather_face_source(step);
        out0 = gather_face_target(step);
    } else if (r.iteration == bounces) {
        mode = 1;
    } else {
        mode = 2;
        // Grid texels in walls are not listed: zero (the upsample may fall back to one).
        r.cmd.barrier_compute_to_transfer();
        r.clear(Tex::gather_ground);
        r.cmd.barrier_transfer_to_compute();
    }
    const int rows = mode == 0 ? s.face_rows : mode == 2 ? s.ground_rows : 0;
    if (mode != 1 && rows == 0) return; // nothing to gather (the face texture is never read)
    // Faces not computed are bound to another allocated texture and never read or written.
    Tex first_direct = Tex::gather_face_a, first_indirect = Tex::gather_face_a;
    for (int face = 3; face >= 0; --face)
        if (computes_face(faces, face)) {
            first_direct = direct_face(face);
            first_indirect = Tex(int(Tex::wall_indirect_px) + face);
        }
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls()).uniform_buffer(1, r.proxies());
    for (int face = 0; face < 4; ++face)
        writes.uniform_texel_buffer(std::uint32_t(2 + face),
                                    r.view(computes_face(faces, face) ? direct_face(face) : first_direct));
    writes.uniform_texel_buffer(6, r.view(previous ? source : out0))
        .uniform_texel_buffer(7, s.directions.view)
        .uniform_texel_buffer(8, s.noise.view)
        .uniform_texel_buffer(13, mode == 0 ? s.faces.view : mode == 2 ? s.ground.view : s.noise.view)
        .uniform_texel_buffer(14, s.materials.view);
    if (mode == 1) {
        for (int face = 0; face < 4; ++face) {
            const Tex t = Tex(int(Tex::wall_indirect_px) + face);
            writes.storage_buffer(std::uint32_t(9 + face), r.buffer(computes_face(faces, face) ? t : first_indirect));
        }
    } else {
        for (int b = 9; b < 13; ++b) writes.storage_buffer(std::uint32_t(b), r.buffer(out0));
    }
    const std::uint32_t features = std::uint32_t(mode) | (previous ? 4u : 0u);
    r.cmd.bind(r.pipeline<GatherParams>("gi_gather.comp", {.proxies = false, .features = features, .faces = faces}));
    r.cmd.push_descriptors(writes);
    const glm::ivec2 size = mode == 1 ? glm::ivec2(in.window.width, in.window.height) : glm::ivec2(list_width, rows);
    auto p = r.params<GatherParams>(size.x, size.y);
    const PackedGatherFrame packed = pack(f);
    p.pass = {.origin_x = packed.origin_x,
              .origin_z = packed.origin_z,
              .offset = packed.offset,
              .tiles = packed.tiles,
              .rays = mode == 0 ? in.settings.gather.face_rays : in.settings.gather.rays,
              .noise = f.noise_origin.x | (f.noise_origin.y << 8) | (g.scale << 16),
              .window = packed.window};
    r.cmd.push_constants(p);
    r.dispatch(size.x, size.y);
    r.cmd.barrier_compute_to_compute();
}

FaceTextures direct_faces(const ReferenceStore& store) {
    FaceTextures d{};
    for (int face = 0; face < 4; ++face) d[std::size_t(face)] = store.find(direct_face(face));
    return d;
}

void reference_gather_row(ReferenceContext& c) {
    const FrameInputs& in = c.in;
    const int bounces = in.settings.gather.bounces;
    if (!has_sources(in)) {
        const HeatGrid g = gather_grid(in);
        c.store.put(Tex::gather_ground, Texture("gather_ground", TexFormat::rgba16f, g.width, g.height));
        c.store.put(Tex::indirect, Texture("indirect", TexFormat::rgba16f, in.window.width, in.window.height));
        return;
    }
    if (c.iteration < bounces) {
        const int step = face_step(in, c.history, c.iteration);
        const Texture* previous = step > 0 ? c.store.find(gather_face_source(step)) : nullptr;
        c.store.put(gather_face_target(step), reference_gather_faces(in, direct_faces(c.store), previous, c.options));
    } else if (c.iteration == bounces) {
        auto faces = reference_gather_fill(in, c.store.at(final_faces(in, c.history)), c.options);
        for (int face = 0; face < 4; ++face)
            if (faces[std::size_t(face)].width > 0)
                c.store.put(Tex(int(Tex::wall_indirect_px) + face), std::move(faces[std::size_t(face)]));
    } else if (c.iteration == bounces + 1) {
        c.store.put(Tex::gather_ground, reference_gather_ground(in, direct_faces(c.store),
                                                                c.store.at(final_faces(in, c.history)), c.options));
    } else {
        c.store.put(Tex::indirect, reference_upsample(in, gather_grid(in), c.store.at(Tex::gather_ground), c.options));
    }
}

TexSet gather_writes(const FrameInputs& in) {
    TexSet set;
    set.add(Tex::gather_ground).add(Tex::indirect);
    if (!has_sources(in)) return set;
    set.add(Tex::gather_face_a).add(Tex::gather_face_b);
    const std::uint32_t faces = computed_faces(in.settings);
    for (int face = 0; face < 4; ++face)
        if (computes_face(faces, face)) set.add(Tex(int(Tex::wall_indirect_px) + face));
    return set;
}

constexpr Tex gather_reads[] = {Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz,
                                Tex::wall_direct_nz, Tex::gather_face_a,  Tex::gather_face_b};
constexpr Tex gather_keeps[] = {Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz,
                                Tex::wall_direct_nz};
constexpr std::string_view gather_settings[] = {
    "gather.scale",  "gather.rays",   "gather.face_rays", "gather.bounces", "gather.frames",
    "wall_albedo",   "albedo_boost",  "wall_lighting",    "wall_faces.px",  "wall_faces.nx",
    "wall_faces.pz", "wall_faces.nz"};

} // namespace

constinit const PassRow gather{
    .pass = Pass::gather,
    .name = "gather",
    .reads = gather_reads,
    .writes_for = gather_writes,
    .settings = gather_settings,
    .inputs = input_walls,
    .iterations = gather_iterations,
    .converge_frames = gather_frames,
    .history_keeps = gather_keeps,
    .record = record_gather,
    .reference = reference_gather_row,
};

} // namespace lantern::gi::rows
