// The baked row (docs/baked.md, "At run time"): the bake's light, stored as seed 002's brick
// atlas (FrameInputs::baked), added to the indirect textures after the method's own rows.
// In place: it reads what the method wrote and adds to it, so the method's rows rerun when
// it changes (derive_keys: later rows that overwrite an output in place); where no earlier
// row wrote a texture this frame it writes it.
#include "rows/rows.hpp"

#include "lantern/gi/baked_light.hpp"
#include "lantern/gi/reference.hpp"
#include "reference_util.hpp"

#include <cstring>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;
using ref_util::for_each_row;

constexpr Tex face_tex(int f) { return Tex(int(Tex::wall_indirect_px) + f); }

// The faces the row adds to: those the frame computes, when walls are lit.
std::uint32_t baked_faces(const FrameInputs& in) { return in.settings.wall_lighting ? computed_faces(in.settings) : 0u; }

TexSet baked_writes(const FrameInputs& in) {
    TexSet set;
    set.add(Tex::indirect);
    const std::uint32_t faces = baked_faces(in);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) set.add(face_tex(f));
    return set;
}

const char* baked_not_needed(const FrameInputs& in, bool, bool) {
    if (!in.baked) return "no baked light";
    const BakedLight& b = *in.baked;
    const GiWindow& w = in.window;
    const float x0 = float(b.origin.x), z0 = float(b.origin.y);
    const float x1 = x0 + float(b.width) / float(b.resolution), z1 = z0 + float(b.height) / float(b.resolution);
    if (b.width <= 0 || b.height <= 0 || w.view.min_x >= x1 || w.view.min_z >= z1 || w.view.min_x + w.view.width <= x0 ||
        w.view.min_z + w.view.height <= z0)
        return "no baked light in the GI window";
    return nullptr;
}

// Whether a planned row before the baked row writes `t` this frame (then the row adds to it).
bool written_earlier(const FrameInputs& in, const PassPlan& plan, Tex t) {
    for (const PassRow* row : method(in.settings.method).rows) {
        if (row->pass == Pass::baked) return false;
        if (plan.run.has(row->pass) && row->outputs(in).has(t)) return true;
    }
    return false;
}

bool faces_written_earlier(const FrameInputs& in, const PassPlan& plan) {
    const std::uint32_t faces = baked_faces(in);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) return written_earlier(in, plan, face_tex(f));
    return false;
}

struct BakedParams {
    std::int32_t origin_x = 0, origin_z = 0, resolution = 0, width = 0, height = 0, add_ground = 0, add_faces = 0, pad0 = 0;
};

// The atlas and indirection as images, uploaded when the baked light changes (the old ones
// are destroyed deferred: freed once the submissions that read them completed, the seed's
// "retired one load later").
struct BakedState : vk::PassState {
    gpu::Image atlas, indirection;
    gpu::Sampler linear, nearest;
    std::uint64_t key = 0;
    bool uploaded = false;
};

gpu::Image upload_image(PassRecorder& r, std::uint32_t width, std::uint32_t height, VkFormat format,
                        const std::vector<std::uint8_t>& bytes, const char* name) {
    gpu::Image image = r.device().create_image({.width = width, .height = height, .format = format,
                                                .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .name = name});
    gpu::BufferDesc desc;
    desc.size = bytes.size();
    desc.memory = gpu::MemoryKind::upload;
    desc.name = name;
    gpu::Buffer staging = r.device().create_buffer(desc);
    std::memcpy(staging.mapped(), bytes.data(), bytes.size());
    r.cmd.transition(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    r.cmd.copy_buffer_to_image(staging, 0, image);
    r.cmd.transition(image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return image; // the staging buffer is destroyed deferred, after this list ran
}

void record_baked(PassRecorder& r) {
    const FrameInputs& in = r.in;
    const BakedLight& b = *in.baked;
    BakedState& s = r.state<BakedState>();
    if (!s.linear) {
        s.linear = r.device().create_sampler({.filter = VK_FILTER_LINEAR, .name = "baked atlas"});
        s.nearest = r.device().create_sampler({.name = "baked indirection"});
    }
    if (!s.uploaded || s.key != b.key) {
        const BrickAtlas& a = b.bricks;
        s.atlas = upload_image(r, std::uint32_t(a.atlas_width()), std::uint32_t(a.atlas_height()), VK_FORMAT_R8G8B8A8_UNORM,
                               a.atlas, "baked atlas");
        s.indirection = upload_image(r, std::uint32_t(a.cells_x), std::uint32_t(a.cells_y * a.layers),
                                     VK_FORMAT_R8G8B8A8_UINT, a.indirection, "baked indirection");
        s.key = b.key;
        s.uploaded = true;
    }
    const GiWindow& w = in.window;
    const std::uint32_t faces = baked_faces(in);
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls())
        .uniform_buffer(1, r.proxies())
        .combined_image_sampler(2, s.atlas, s.linear)
        .combined_image_sampler(3, s.indirection, s.nearest)
        .storage_buffer(4, r.buffer(Tex::indirect));
    // A face not computed is bound to the ground's buffer and never written.
    for (int f = 0; f < 4; ++f)
        writes.storage_buffer(std::uint32_t(5 + f), r.buffer(computes_face(faces, f) ? face_tex(f) : Tex::indirect));
    r.cmd.bind(r.pipeline<BakedParams>("gi_baked.comp", {.proxies = false, .faces = faces}));
    r.cmd.push_descriptors(writes);
    auto p = r.params<BakedParams>(w.width, w.height);
    p.pass = {.origin_x = b.origin.x, .origin_z = b.origin.y, .resolution = b.resolution, .width = b.width, .height = b.height,
              .add_ground = written_earlier(in, r.plan, Tex::indirect) ? 1 : 0,
              .add_faces = faces_written_earlier(in, r.plan) ? 1 : 0};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

// The texture `t` as an earlier row left it to add to, or a new one to write.
Texture start_from(ReferenceContext& c, Tex t, bool add) {
    const GiWindow& w = c.in.window;
    if (add) {
        if (const Texture* found = c.store.find(t)) return *found;
    }
    return Texture(std::string(texture_row(t).name), TexFormat::rgba16f, w.width, w.height);
}

void reference_baked_row(ReferenceContext& c) {
    const FrameInputs& in = c.in;
    const BakedLight& b = *in.baked;
    const GiWindow& w = in.window;
    const std::uint32_t faces = baked_faces(in);
    const bool add_ground = written_earlier(in, c.plan, Tex::indirect), add_faces = faces_written_earlier(in, c.plan);
    Texture ground = start_from(c, Tex::indirect, add_ground);
    std::array<Texture, 4> face;
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) face[std::size_t(f)] = start_from(c, face_tex(f), add_faces);
    const glm::vec4 face_bits = face_bits_mask(faces);
    for_each_row(w.height, c.options, [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
            const bool wall = in.walls.is_wall(cell.x, cell.y);
            auto add_or_write = [&](Texture& t, glm::vec3 value, bool add, float alpha) {
                const float* old = t.at(x, y);
                const glm::vec4 v = add ? glm::vec4(old[0] + value.r, old[1] + value.g, old[2] + value.b, old[3])
                                        : glm::vec4(value, alpha);
                t.store(x, y, &v.x);
            };
            if (!wall || !add_ground) add_or_write(ground, wall ? glm::vec3(0.0f) : b.sample(0, p), add_ground, 0.0f);
            if (faces == 0) continue;
            const glm::vec4 mask = wall ? wall_face_mask(in.walls, cell) * face_bits : glm::vec4(0.0f);
            for (int f = 0; f < 4; ++f) {
                if (!computes_face(faces, f) || (add_faces && !(mask[f] > 0.0f))) continue;
                const glm::vec3 v = mask[f] > 0.0f ? b.sample(1 + f, p) : glm::vec3(0.0f);
                add_or_write(face[std::size_t(f)], v, add_faces, wall ? 1.0f : 0.0f);
            }
        }
    });
    c.store.put(Tex::indirect, std::move(ground));
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) c.store.put(face_tex(f), std::move(face[std::size_t(f)]));
}

constexpr Tex baked_reads[] = {Tex::indirect, Tex::wall_indirect_px, Tex::wall_indirect_nx, Tex::wall_indirect_pz,
                               Tex::wall_indirect_nz};
constexpr std::string_view baked_settings[] = {"wall_lighting", "wall_faces.px", "wall_faces.nx", "wall_faces.pz",
                                               "wall_faces.nz"};

} // namespace

constinit const PassRow baked{
    .pass = Pass::baked,
    .name = "baked",
    .reads = baked_reads,
    .writes_for = baked_writes,
    .settings = baked_settings,
    .inputs = input_walls | input_baked,
    .not_needed = baked_not_needed,
    .record = record_baked,
    .reference = reference_baked_row,
};

} // namespace lantern::gi::rows
