// The bake's rows (docs/baked.md, "At run time"), after the method's own rows:
//
//   baked_sample  reads the bake's light, stored as seed 002's brick atlas
//                 (FrameInputs::baked), into the window's textures: the ground's light
//                 (baked_ground), each exposed face's (baked_face_*) and the HUD's view;
//                 with a pulsing part, that part apart (baked_pulse_*). Cached: it reruns
//                 only when the bake, the window, the walls or a keyed sun change.
//   baked         adds them to the frame's indirect textures (the pulsing part scaled by
//                 this frame's pulse), and the mixed lights' and mixed suns' direct
//                 light (the mixed row's textures) to the direct ones: a plain add each frame
//                 the method rewrites those. In place: it reads what the earlier rows wrote
//                 and adds to it, so they rerun when it changes (derive_keys: later rows that
//                 overwrite an output in place); where no earlier row wrote an indirect
//                 texture this frame it writes it.
#include "rows/rows.hpp"

#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/reference.hpp"
#include "reference_util.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;
using ref_util::for_each_row;

constexpr Tex face_tex(int f) { return Tex(int(Tex::wall_indirect_px) + f); }
constexpr Tex baked_face_tex(int f) { return Tex(int(Tex::baked_face_px) + f); }
// The pulsing part's texture of layer 0 (the ground) or 1 + f (face f).
constexpr Tex pulse_tex(int layer) { return Tex(int(Tex::baked_pulse_ground) + layer); }

// The faces the bake adds to: those the frame computes, when walls are lit.
std::uint32_t baked_faces(const FrameInputs& in) { return in.settings.wall_lighting ? computed_faces(in.settings) : 0u; }

// Whether the bake covers part of the window (the atlas is sampled).
bool samples_bake(const FrameInputs& in) {
    if (!in.baked) return false;
    const BakedLight& b = *in.baked;
    const GiWindow& w = in.window;
    const float x0 = float(b.origin.x), z0 = float(b.origin.y);
    const float x1 = x0 + float(b.width) / float(b.resolution), z1 = z0 + float(b.height) / float(b.resolution);
    return b.width > 0 && b.height > 0 && w.view.min_x < x1 && w.view.min_z < z1 && w.view.min_x + w.view.width > x0 &&
           w.view.min_z + w.view.height > z0;
}

// The mixed point and emissive lights (the mixed suns aside).
bool has_mixed_lights(const FrameInputs& in) { return !in.mixed_lights.empty() || !in.mixed_emissives.empty(); }
bool has_mixed(const FrameInputs& in) { return has_mixed_lights(in) || has_mixed_suns(in); }

// The direct textures the mixed lights' light goes into, and the mixed row's textures it
// comes from: direct, the faces (wall_direct_*), the upper faces (wall_upper_*).
constexpr Tex mixed_targets[] = {Tex::direct,         Tex::wall_direct_px, Tex::wall_direct_nx,
                                 Tex::wall_direct_pz, Tex::wall_direct_nz, Tex::wall_upper_px,
                                 Tex::wall_upper_nx,  Tex::wall_upper_pz,  Tex::wall_upper_nz};
constexpr Tex mixed_sources[] = {Tex::direct_mixed,         Tex::wall_direct_mixed_px, Tex::wall_direct_mixed_nx,
                                 Tex::wall_direct_mixed_pz, Tex::wall_direct_mixed_nz, Tex::wall_upper_mixed_px,
                                 Tex::wall_upper_mixed_nx,  Tex::wall_upper_mixed_pz,  Tex::wall_upper_mixed_nz};
constexpr Tex mixed_sun_sources[] = {Tex::direct_mixed_sun,         Tex::wall_direct_mixed_sun_px,
                                     Tex::wall_direct_mixed_sun_nx, Tex::wall_direct_mixed_sun_pz,
                                     Tex::wall_direct_mixed_sun_nz, Tex::wall_upper_mixed_sun_px,
                                     Tex::wall_upper_mixed_sun_nx,  Tex::wall_upper_mixed_sun_pz,
                                     Tex::wall_upper_mixed_sun_nz};

// Which of mixed_targets the frame has: direct, the computed faces, their uppers when the
// proxies' shadows are unfolded (what the direct pass writes).
bool mixed_target(const FrameInputs& in, int k) {
    if (k == 0) return true;
    const std::uint32_t faces = computed_faces(in.settings);
    return computes_face(faces, (k - 1) % 4) && (k < 5 || unfolds_proxy_shadows(in));
}

// Whether a planned row before the baked row writes `t` this frame (then the row adds to it).
bool written_earlier(const FrameInputs& in, const PassPlan& plan, Tex t) {
    for (const PassRow* row : method(in.settings.method).rows) {
        if (row->pass == Pass::baked) return false;
        if (plan.run.has(row->pass) && row->outputs(in).has(t)) return true;
    }
    return false;
}

// One texture added to another (rgb; the target's alpha kept), or copied over it (`write`);
// with `scaled`, that texture's rgb times the frame's pulse added to the source's first.
struct AddPair {
    Tex source, target;
    bool write = false;
    std::optional<Tex> scaled{};
};

// Whether the frame's bake has a pulsing part (the sampling row keeps it apart).
bool pulses(const FrameInputs& in) { return in.baked && in.baked->pulsing; }

// What the baked row does this frame, in three groups (one dispatch each): the baked light,
// the mixed lights' direct light and the mixed suns' (with `all`, each as if present: the
// variants a later frame may need). The mixed row is planned whenever a bake is in use.
constexpr std::size_t baked_group = 0, mixed_lights_group = 1, mixed_suns_group = 2;
std::array<std::vector<AddPair>, 3> add_pairs(const FrameInputs& in, const PassPlan& plan, bool all = false) {
    std::array<std::vector<AddPair>, 3> out;
    if (all || samples_bake(in)) {
        const bool pulsing = all || pulses(in);
        const auto scaled = [&](int layer) { return pulsing ? std::optional(pulse_tex(layer)) : std::nullopt; };
        out[baked_group].push_back({Tex::baked_ground, Tex::indirect, !written_earlier(in, plan, Tex::indirect), scaled(0)});
        const std::uint32_t faces = baked_faces(in);
        for (int f = 0; f < 4; ++f)
            if (computes_face(faces, f))
                out[baked_group].push_back({baked_face_tex(f), face_tex(f), !written_earlier(in, plan, face_tex(f)), scaled(1 + f)});
    }
    const bool mixed_row = all || plan.run.has(Pass::mixed);
    for (int k = 0; k < 9; ++k)
        if (mixed_target(in, k)) {
            if (mixed_row && (all || has_mixed_lights(in))) out[mixed_lights_group].push_back({mixed_sources[k], mixed_targets[k]});
            if (mixed_row && (all || has_mixed_suns(in))) out[mixed_suns_group].push_back({mixed_sun_sources[k], mixed_targets[k]});
        }
    return out;
}

// ---- baked_sample

TexSet sample_writes(const FrameInputs& in) {
    TexSet set;
    set.add(Tex::baked_ground).add(Tex::baked_view);
    const std::uint32_t faces = baked_faces(in);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) set.add(baked_face_tex(f));
    if (pulses(in)) {
        set.add(pulse_tex(0));
        for (int f = 0; f < 4; ++f)
            if (computes_face(faces, f)) set.add(pulse_tex(1 + f));
    }
    return set;
}

const char* sample_not_needed(const FrameInputs& in, bool, bool) {
    if (samples_bake(in)) return nullptr;
    return in.baked ? "no baked light in the GI window" : "no baked light";
}

struct SampleParams {
    std::int32_t origin_x = 0, origin_z = 0, resolution = 0, width = 0, height = 0;
    // Bit 0: the atlas holds the pulsing part (layers 5..9), written apart; bits 1..: the
    // moving sun's (baked_sun_of) atlas layer of the key below its time, plus 1 (0: no keyed sun).
    std::int32_t parts = 0;
    float intensity = 1.0f;
    std::int32_t offset = 0; // the dispatch's first texel, x | y << 16
};

// The atlas and indirection as images, rewritten when the baked light changes. Each keeps a
// capacity that only grows (doubling): the device memory steadies as bakes come and go
// instead of following every composition, and the images are never re-created in a steady
// world. Old images are destroyed deferred: freed once the submissions that read them
// completed (seed 002's "retired one load later").
struct SampleState : vk::PassState {
    gpu::Image atlas, indirection;
    gpu::Sampler linear, nearest;
    UploadedArray sun; // the keys' weights: colour x (1 - blend), colour x blend (BakedLight::light)
    std::uint64_t key = 0;
    bool uploaded = false;
    WindowScroll scroll; // at a window step, the shared texels are shifted, not sampled again
};

std::uint32_t grown(std::uint32_t have, std::uint32_t need) {
    std::uint32_t c = std::max<std::uint32_t>(have, 1);
    while (c < need) c *= 2;
    return c;
}

// Writes `rows` rows of `width` RGBA8 texels (`bytes`) into the top-left of `image`, the rest
// zero; grows the image first (to at least `capacity_rows`) when it is smaller.
void upload_into(PassRecorder& r, gpu::Image& image, std::uint32_t width, std::uint32_t rows, std::uint32_t capacity_rows,
                 VkFormat format, const std::vector<std::uint8_t>& bytes, const char* name) {
    const bool fits = image && image.width() >= width && image.height() >= rows;
    if (!fits) {
        const std::uint32_t w = grown(image ? image.width() : 0, width),
                            h = grown(image ? image.height() : 0, std::max(rows, capacity_rows));
        image = r.device().create_image({.width = w, .height = h, .format = format, .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .name = name});
    }
    gpu::BufferDesc desc;
    desc.size = VkDeviceSize(image.width()) * image.height() * 4;
    desc.memory = gpu::MemoryKind::upload;
    desc.name = name;
    gpu::Buffer staging = r.device().create_buffer(desc); // destroyed deferred, after this list ran
    std::memset(staging.mapped(), 0, desc.size);
    for (std::uint32_t y = 0; y < rows; ++y)
        std::memcpy(staging.mapped() + std::size_t(y) * image.width() * 4, bytes.data() + std::size_t(y) * width * 4, std::size_t(width) * 4);
    // An image in use was read by earlier frames' shaders: they finish before the copy.
    r.cmd.transition(image, fits ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    r.cmd.copy_buffer_to_image(staging, 0, image);
    r.cmd.transition(image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void record_sample(PassRecorder& r) {
    const FrameInputs& in = r.in;
    const BakedLight& b = *in.baked;
    SampleState& s = r.state<SampleState>();
    if (!s.linear) {
        s.linear = r.device().create_sampler({.filter = VK_FILTER_LINEAR, .name = "baked atlas"});
        s.nearest = r.device().create_sampler({.name = "baked indirection"});
    }
    if (!s.uploaded || s.key != b.key) {
        const BrickAtlas& a = b.bricks;
        // Room for every cell of the rectangle as a brick of its own (the most a composition
        // of its size can hold), so a moving world keeps its images.
        const std::uint32_t most = std::uint32_t(a.cells_x * a.cells_y * a.layers);
        const std::uint32_t most_rows = (most + std::uint32_t(a.atlas_bricks_x) - 1) / std::uint32_t(a.atlas_bricks_x) * brick_texels;
        upload_into(r, s.atlas, std::uint32_t(a.atlas_width()), std::uint32_t(a.atlas_height()), most_rows,
                    VK_FORMAT_R8G8B8A8_UNORM, a.atlas, "baked atlas");
        upload_into(r, s.indirection, std::uint32_t(a.cells_x), std::uint32_t(a.cells_y * a.layers), 0,
                    VK_FORMAT_R8G8B8A8_UINT, a.indirection, "baked indirection");
        s.key = b.key;
        s.uploaded = true;
    }
    const BakedSun sun = baked_sun_of(in);
    const glm::vec4 weights[2] = {glm::vec4(sun.color * (1.0f - sun.blend), 0.0f), glm::vec4(sun.color * sun.blend, 0.0f)};
    upload_array(r, s.sun, std::span<const glm::vec4>(weights), VK_FORMAT_R32G32B32A32_SFLOAT, "baked sun");
    r.cmd.barrier_transfer_to_compute();
    const GiWindow& w = in.window;
    const std::uint32_t faces = baked_faces(in);
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls())
        .uniform_buffer(1, r.proxies())
        .combined_image_sampler(2, s.atlas, s.linear)
        .combined_image_sampler(3, s.indirection, s.nearest)
        .storage_buffer(4, r.buffer(Tex::baked_ground));
    // A face not computed is bound to the ground's buffer and never written.
    for (int f = 0; f < 4; ++f)
        writes.storage_buffer(std::uint32_t(5 + f), r.buffer(computes_face(faces, f) ? baked_face_tex(f) : Tex::baked_ground));
    writes.storage_buffer(9, r.buffer(Tex::baked_view));
    writes.uniform_texel_buffer(10, s.sun.view);
    // The pulsing part's, bound to the steady ground's (never written) without one.
    for (int layer = 0; layer < baked_layers; ++layer) {
        const bool written = b.pulsing && (layer == 0 || computes_face(faces, layer - 1));
        writes.storage_buffer(std::uint32_t(11 + layer), r.buffer(written ? pulse_tex(layer) : Tex::baked_ground));
    }
    const int sun_first = sun.key >= 0 && sun.key + 1 < b.sun_keys ? b.sun_layer(sun.key, 0) + 1 : 0;
    // The parts as the shader's FEATURES (bit 0 pulsing, bit 1 keyed sun), so the variant
    // without them has none of their reads; the variants another composition or time of
    // day may need are compiled before a frame asks for them.
    const std::uint32_t features = (b.pulsing ? 1u : 0u) | (sun_first != 0 ? 2u : 0u);
    for (std::uint32_t other = 0; other < 4; ++other)
        if (other != features && ((other & 2u) == 0 || b.sun_keys > 1))
            r.prefetch_pipeline<SampleParams>("gi_baked.comp", {.proxies = false, .features = other, .faces = faces});
    // Scrolling (rows.hpp WindowScroll): a texel depends on its world point (the atlas, the
    // sun keys' weights, the intensity) and on the walls of its tile and the four beside it.
    std::vector<Tex> outputs;
    sample_writes(in).for_each([&](Tex t) { outputs.push_back(t); });
    Hasher h;
    h.add(b.key).add(b.origin.x).add(b.origin.y).add(b.resolution).add(b.width).add(b.height).add(b.pulsing);
    h.add(features).add(sun_first).add_bytes(weights, sizeof weights).add(in.settings.baked_intensity).add(faces);
    h.add(w.resolution).add(w.width).add(w.height);
    glm::ivec2 shift(0);
    const bool scrolls = scroll_from_last(r, s.scroll, h.value(), outputs, 1, glm::ivec2(1), shift);

    r.cmd.bind(r.pipeline<SampleParams>("gi_baked.comp", {.proxies = false, .features = features, .faces = faces}));
    r.cmd.push_descriptors(writes);
    auto p = r.params<SampleParams>(w.width, w.height);
    p.pass = {.origin_x = b.origin.x, .origin_z = b.origin.y, .resolution = b.resolution, .width = b.width, .height = b.height,
              .parts = (b.pulsing ? 1 : 0) | (sun_first << 1), .intensity = in.settings.baked_intensity};
    dispatch_scrolled(r, s.scroll, scrolls, shift, outputs, 8 /* rgba16f */, 1, [&](int x0, int y0) {
        p.pass.offset = x0 | (y0 << 16);
        r.cmd.push_constants(p);
    });
    r.cmd.barrier_compute_to_compute();
}

void reference_sample_row(ReferenceContext& c) {
    const FrameInputs& in = c.in;
    const BakedLight& b = *in.baked;
    const GiWindow& w = in.window;
    const std::uint32_t faces = baked_faces(in);
    const bool pulsing = b.pulsing;
    // Layer 0 the ground's, 1 + f face f's; the steady part (with a keyed sun's) and the
    // pulsing part at pulse 1.
    std::array<Texture, baked_layers> steady, pulse;
    for (int layer = 0; layer < baked_layers; ++layer) {
        if (layer > 0 && !computes_face(faces, layer - 1)) continue;
        const std::size_t l = std::size_t(layer);
        steady[l] = Texture(tex_name(layer == 0 ? Tex::baked_ground : baked_face_tex(layer - 1)), TexFormat::rgba16f, w.width, w.height);
        if (pulsing) pulse[l] = Texture(tex_name(pulse_tex(layer)), TexFormat::rgba16f, w.width, w.height);
    }
    Texture view("baked_view", TexFormat::rgba16f, w.width, w.height);
    const glm::vec4 face_bits = face_bits_mask(faces);
    const float k = in.settings.baked_intensity;
    const BakedSun sun = baked_sun_of(in);
    for_each_row(w.height, c.options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
            const bool wall = in.walls.is_wall(cell.x, cell.y);
            const glm::vec4 mask = wall && faces != 0 ? wall_face_mask(in.walls, cell) * face_bits : glm::vec4(0.0f);
            glm::vec4 shown(0.0f); // the HUD's: the light at pulse 1, the first layer's level + 1
            for (int layer = 0; layer < baked_layers; ++layer) {
                if (layer > 0 && !computes_face(faces, layer - 1)) continue;
                const bool taken = layer == 0 ? !wall : mask[layer - 1] > 0.0f;
                const float alpha = layer > 0 && wall ? 1.0f : 0.0f; // as wall_indirect writes faces
                const glm::vec3 v = taken ? (b.sample(layer, p) + b.sun_light(layer, p, sun)) * k : glm::vec3(0.0f);
                const glm::vec4 texel(v, alpha);
                steady[std::size_t(layer)].store(x, y, &texel.x);
                glm::vec3 shown_v = v;
                if (pulsing) {
                    const glm::vec3 pv = taken ? b.sample(baked_layers + layer, p) * k : glm::vec3(0.0f);
                    const glm::vec4 ptexel(pv, alpha);
                    pulse[std::size_t(layer)].store(x, y, &ptexel.x);
                    shown_v += pv;
                }
                if (taken) {
                    shown += glm::vec4(shown_v, 0.0f);
                    if (shown.a == 0.0f) shown.a = float(b.level(layer, p) + 1);
                }
            }
            view.store(x, y, &shown.x);
        }
    });
    c.store.put(Tex::baked_view, std::move(view));
    for (int layer = 0; layer < baked_layers; ++layer) {
        if (layer > 0 && !computes_face(faces, layer - 1)) continue;
        c.store.put(layer == 0 ? Tex::baked_ground : baked_face_tex(layer - 1), std::move(steady[std::size_t(layer)]));
        if (pulsing) c.store.put(pulse_tex(layer), std::move(pulse[std::size_t(layer)]));
    }
}

// ---- baked: the adds

TexSet baked_writes(const FrameInputs& in) {
    TexSet set;
    if (samples_bake(in)) {
        set.add(Tex::indirect);
        const std::uint32_t faces = baked_faces(in);
        for (int f = 0; f < 4; ++f)
            if (computes_face(faces, f)) set.add(face_tex(f));
    }
    if (has_mixed(in))
        for (int k = 0; k < 9; ++k)
            if (mixed_target(in, k)) set.add(mixed_targets[k]);
    return set;
}

const char* baked_not_needed(const FrameInputs& in, bool, bool) {
    if (samples_bake(in) || has_mixed(in)) return nullptr;
    return in.baked ? "no baked light in the GI window" : "no baked light";
}

constexpr int pairs_per_dispatch = 9; // gi_add.comp's
constexpr int scaled_pairs = 5;       // the first pairs that may add a scaled texture

constexpr std::uint32_t feature_list = 1u << 14;   // gi_add.comp: the workgroups listed alone
constexpr std::uint32_t feature_blocks = 1u << 13; // gi_add.comp: the blocks listed alone

// gi_add.comp's parameters: the scaled textures' factor; with a list, the grid's width.
struct AddParams {
    float scale = 1.0f;
    std::int32_t groups_x = 0;
    std::int32_t blocks = 0; // with a list of blocks, its length
    std::int32_t unused2 = 0, unused3 = 0, unused4 = 0, unused5 = 0, unused6 = 0;
};

// The workgroups the mixed lights' group records: those a mixed point light or emissive can
// reach (bin_lights, the mixed row's own bins), where their set is not all zeros. The others
// would add zeros, which leave every texel as it is (x + 0 = x, the alpha kept). All of them
// without dirty bins (the full dispatch the listed one is compared with); none when no mixed
// light reaches the window. The mixed suns' group records every workgroup (a sun lights
// every texel). Each group its own lists: the uploads of one command buffer.
struct AddState : vk::PassState {
    // Per group (add_pairs' order): the ground pair's list of workgroups (the mixed lights'),
    // or a stand-in bound when its dispatch is full; the face pairs' blocks (rows::wall_blocks,
    // of the listed workgroups).
    std::array<UploadedArray, 3> groups, blocks;
};

// gi_add.comp's FEATURES for a group: bit k pair k used, bit 16 + k pair k copies, bit 15
// pairs 0..scaled_pairs - 1 add their scaled texture.
std::uint32_t add_features(std::span<const AddPair> pairs) {
    std::uint32_t features = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        features |= (1u << k) | (pairs[k].write ? 1u << (16 + k) : 0u);
        if (pairs[k].scaled) {
            LANTERN_ASSERT(k < std::size_t(scaled_pairs), "gi_add.comp scales its first pairs only");
            features |= 1u << 15;
        }
    }
    return features;
}

// The workgroups the mixed lights (not the suns) reach, or nullopt for all of them
// (mixed_add_bins without the suns).
std::optional<std::vector<std::uint32_t>> mixed_light_bins(const PassRecorder& r, WorkgroupGrid grid);

// The listed workgroups of the mixed lights' group's adds (AddState), or nullopt for all of them.
std::optional<std::vector<std::uint32_t>> mixed_add_groups(PassRecorder& r, Tex target) {
    const WorkgroupGrid grid = workgroup_grid(r, r.pitch(target), r.in.window.height);
    std::optional<std::vector<std::uint32_t>> list = mixed_light_bins(r, grid);
    r.count_workgroups(grid.x * grid.y, list ? list->size() : grid.x * grid.y);
    return list;
}

// Whether the face pairs of a group (pairs 1..: add_pairs puts the ground's first) add, so
// that they may skip the blocks where their sources are zeros; a pair that copies writes
// every texel.
bool faces_add(std::span<const AddPair> pairs) {
    return pairs.size() > 1 && std::none_of(pairs.begin() + 1, pairs.end(), [](const AddPair& p) { return p.write; });
}

// Records gi_add.comp over `pairs`: every workgroup, the workgroups in `groups` (LIST), or
// the blocks in `blocks` (BLOCKS), the list uploaded into `list_buffer`.
void record_add(PassRecorder& r, std::span<const AddPair> pairs, const std::vector<std::uint32_t>* groups,
                const std::vector<std::uint32_t>* blocks, UploadedArray& list_buffer) {
    upload_list(r, list_buffer, groups ? groups : blocks, "gi add workgroups");
    gpu::DescriptorWrites writes;
    for (int k = 0; k < pairs_per_dispatch; ++k) {
        // Unused slots are bound to the first pair's textures and never touched.
        const AddPair& p = std::size_t(k) < pairs.size() ? pairs[std::size_t(k)] : pairs[0];
        writes.uniform_texel_buffer(std::uint32_t(k), r.view(p.source));
        writes.storage_buffer(std::uint32_t(pairs_per_dispatch + k), r.buffer(p.target));
    }
    for (int k = 0; k < scaled_pairs; ++k) {
        const AddPair& p = std::size_t(k) < pairs.size() && pairs[std::size_t(k)].scaled ? pairs[std::size_t(k)] : pairs[0];
        writes.uniform_texel_buffer(std::uint32_t(2 * pairs_per_dispatch + k), r.view(p.scaled.value_or(p.source)));
    }
    writes.storage_buffer(std::uint32_t(2 * pairs_per_dispatch + scaled_pairs), list_buffer.buffer);
    const std::uint32_t features = add_features(pairs) | (groups ? feature_list : 0u) | (blocks ? feature_blocks : 0u);
    r.cmd.bind(r.pipeline<AddParams>("gi_add.comp", {.proxies = false, .features = features}));
    r.cmd.push_descriptors(writes);
    auto params = r.params<AddParams>(r.in.window.width, r.in.window.height);
    params.pass.scale = r.in.baked_pulse;
    params.pass.groups_x = std::int32_t(workgroup_grid(r, r.pitch(pairs[0].target), r.in.window.height).x);
    params.pass.blocks = blocks ? std::int32_t(blocks->size()) : 0;
    r.cmd.push_constants(params);
    if (groups)
        r.cmd.dispatch(std::uint32_t(groups->size()), 1);
    else if (blocks)
        dispatch_listed_blocks(r, blocks->size());
    else
        r.dispatch(r.in.window.width, r.in.window.height);
    r.cmd.barrier_compute_to_compute();
}

void record_baked(PassRecorder& r) {
    AddState& s = r.state<AddState>();
    const std::array<std::vector<AddPair>, 3> groups = add_pairs(r.in, r.plan);
    for (std::size_t group = 0; group < groups.size(); ++group) {
        const std::vector<AddPair>& pairs = groups[group];
        if (pairs.empty()) continue;
        // The mixed lights' group: the workgroups they reach (or all of them).
        std::optional<std::vector<std::uint32_t>> list;
        if (group == mixed_lights_group) {
            list = mixed_add_groups(r, pairs[0].target);
            if (list && list->empty()) continue; // no mixed light reaches the window
        }
        UploadedArray& list_buffer = s.groups[group];
        UploadedArray& block_buffer = s.blocks[group];
        // The faces' pairs only in the blocks holding a wall texel (of the listed workgroups),
        // where partial recording is on and some block holds none (the renderer without it
        // adds everywhere: the full dispatch the listed one is compared with).
        std::optional<std::vector<std::uint32_t>> blocks =
            r.dirty_bins() && faces_add(pairs) ? wall_blocks(r.in, int(r.block_h()), 65535u * r.group_x() * r.group_y())
                                               : std::nullopt;
        if (!blocks) {
            record_add(r, pairs, list ? &*list : nullptr, nullptr, list_buffer);
            continue;
        }
        if (list) {
            const WorkgroupGrid grid = workgroup_grid(r, r.pitch(pairs[0].target), r.in.window.height);
            std::vector<bool> listed(std::size_t(grid.x) * grid.y);
            for (const std::uint32_t g : *list) listed[g] = true;
            std::erase_if(*blocks, [&](std::uint32_t b) {
                const std::uint32_t gx = (b & 0xFFFFu) / r.group_x(), gy = (b >> 16) / r.group_y();
                return !listed[std::size_t(gy) * grid.x + gx];
            });
        }
        record_add(r, std::span(pairs).first(1), list ? &*list : nullptr, nullptr, list_buffer);
        if (!blocks->empty())
            record_add(r, std::span(pairs).subspan(1), nullptr, &*blocks, block_buffer);
    }
    // The other variants, before a frame needs them (creating one then stalls that frame: a
    // mixed light coming into view, the bake covering the window, or walls coming into it).
    const std::array<std::vector<AddPair>, 3> all = add_pairs(r.in, r.plan, true);
    for (std::size_t group = 0; group < all.size(); ++group) {
        if (all[group].empty()) continue;
        r.prefetch_pipeline<AddParams>("gi_add.comp", {.proxies = false, .features = add_features(all[group])});
        const std::uint32_t listed = group == mixed_lights_group ? feature_list : 0u; // its listed variants
        if (listed) r.prefetch_pipeline<AddParams>("gi_add.comp", {.proxies = false, .features = add_features(all[group]) | listed});
        if (r.dirty_bins() && faces_add(all[group])) { // the ground alone, the faces by blocks
            const std::uint32_t ground = add_features(std::span(all[group]).first(1));
            r.prefetch_pipeline<AddParams>("gi_add.comp", {.proxies = false, .features = ground});
            if (listed) r.prefetch_pipeline<AddParams>("gi_add.comp", {.proxies = false, .features = ground | listed});
            r.prefetch_pipeline<AddParams>(
                "gi_add.comp",
                {.proxies = false, .features = add_features(std::span(all[group]).subspan(1)) | feature_blocks});
        }
    }
}

void reference_baked_row(ReferenceContext& c) {
    for (const std::vector<AddPair>& group : add_pairs(c.in, c.plan))
    for (const AddPair& p : group) {
        const Texture* found = c.store.find(p.source);
        if (!found) continue;
        Texture add = *found; // with the scaled texture's part (gi_add.comp: source + scale x scaled)
        if (const Texture* scaled = p.scaled ? c.store.find(*p.scaled) : nullptr)
            for (int y = 0; y < add.height; ++y)
                for (int x = 0; x < add.width; ++x) {
                    const float* a = add.at(x, y);
                    const float* b = scaled->at(x, y);
                    const float pulse = c.in.baked_pulse;
                    const float v[4] = {a[0] + pulse * b[0], a[1] + pulse * b[1], a[2] + pulse * b[2], a[3]};
                    add.store(x, y, v);
                }
        if (p.write || !c.store.find(p.target)) {
            c.store.put(p.target, std::move(add));
            continue;
        }
        Texture sum = c.store.at(p.target);
        for (int y = 0; y < sum.height; ++y)
            for (int x = 0; x < sum.width; ++x) {
                const float* a = sum.at(x, y);
                const float* b = add.at(x, y);
                const float v[4] = {a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3]};
                sum.store(x, y, v);
            }
        c.store.put(p.target, std::move(sum));
    }
}

constexpr std::string_view sample_settings[] = {"wall_lighting", "wall_faces.px", "wall_faces.nx", "wall_faces.pz",
                                                "wall_faces.nz", "baked_intensity"};
constexpr Tex baked_reads[] = {Tex::indirect,          Tex::wall_indirect_px,     Tex::wall_indirect_nx,
                               Tex::wall_indirect_pz,  Tex::wall_indirect_nz,     Tex::direct,
                               Tex::wall_direct_px,    Tex::wall_direct_nx,       Tex::wall_direct_pz,
                               Tex::wall_direct_nz,    Tex::wall_upper_px,        Tex::wall_upper_nx,
                               Tex::wall_upper_pz,     Tex::wall_upper_nz,        Tex::direct_mixed,
                               Tex::wall_direct_mixed_px, Tex::wall_direct_mixed_nx, Tex::wall_direct_mixed_pz,
                               Tex::wall_direct_mixed_nz, Tex::wall_upper_mixed_px,  Tex::wall_upper_mixed_nx,
                               Tex::wall_upper_mixed_pz,  Tex::wall_upper_mixed_nz,  Tex::direct_mixed_sun,
                               Tex::wall_direct_mixed_sun_px, Tex::wall_direct_mixed_sun_nx, Tex::wall_direct_mixed_sun_pz,
                               Tex::wall_direct_mixed_sun_nz, Tex::wall_upper_mixed_sun_px,  Tex::wall_upper_mixed_sun_nx,
                               Tex::wall_upper_mixed_sun_pz,  Tex::wall_upper_mixed_sun_nz,  Tex::baked_ground,
                               Tex::baked_face_px,        Tex::baked_face_nx,        Tex::baked_face_pz,
                               Tex::baked_face_nz,        Tex::baked_pulse_ground,   Tex::baked_pulse_face_px,
                               Tex::baked_pulse_face_nx,  Tex::baked_pulse_face_pz,  Tex::baked_pulse_face_nz};
// With the probe row's settings too: the probes read the wall textures this row adds to in
// place, so a change that reruns them must rerun the rows they read (this row's own key
// changes, and so do the keys of the rows it adds to), or they would read last frame's sums.
constexpr std::string_view baked_settings[] = {"wall_lighting", "wall_faces.px", "wall_faces.nx", "wall_faces.pz",
                                               "wall_faces.nz", "proxy_wall_shadows", "baked_intensity",
                                               "probe_rays", "wall_albedo", "albedo_boost"};

} // namespace

std::optional<std::vector<std::uint32_t>> mixed_add_bins(const PassRecorder& r, WorkgroupGrid grid) {
    return has_mixed_suns(r.in) ? std::nullopt : mixed_light_bins(r, grid);
}

namespace {
std::optional<std::vector<std::uint32_t>> mixed_light_bins(const PassRecorder& r, WorkgroupGrid grid) {
    if (!r.dirty_bins()) return std::nullopt;
    const std::uint32_t count = grid.x * grid.y;
    const std::vector<std::uint64_t> bins = bin_lights(r.in.mixed_lights, r.in.mixed_emissives, r.in.window, grid.x, grid.y,
                                                       float(4 * r.group_x()), float(r.block_h() * r.group_y()));
    std::vector<std::uint32_t> list;
    for (std::uint32_t b = 0; b < count; ++b)
        if (bins[b] != no_light_bin) list.push_back(b);
    if (list.size() == count || list.size() > 65535) return std::nullopt;
    return list;
}
} // namespace

constinit const PassRow baked_sample{
    .pass = Pass::baked_sample,
    .name = "baked_sample",
    .writes_for = sample_writes,
    .settings = sample_settings,
    .inputs = input_walls | input_baked,
    .not_needed = sample_not_needed,
    .record = record_sample,
    .reference = reference_sample_row,
};

constinit const PassRow baked{
    .pass = Pass::baked,
    .name = "baked",
    .reads = baked_reads,
    .writes_for = baked_writes,
    .settings = baked_settings,
    // What the sampling and mixed rows wrote changes only with these (their other inputs and
    // settings are listed here too, or are the direct row's), and listing them makes this
    // row's own key change with them, so the rows it adds to in place rerun first
    // (derive_keys hashes a later in-place writer's own key, not its reads).
    .inputs = input_walls | input_baked | input_baked_pulse | input_walls_in_window | input_mixed_lights,
    .not_needed = baked_not_needed,
    .record = record_baked,
    .reference = reference_baked_row,
};

} // namespace lantern::gi::rows
