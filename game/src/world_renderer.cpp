// The game's world renderer: box faces, frame constants, one draw per face group.
#include "lantern/game/world_renderer.hpp"

#include "lantern/game/settings.hpp"

#include "lantern/gi/probes.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/command_list.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/render/stream_buffer.hpp"

#include "lantern_game_shaders.hpp"

#include <glm/common.hpp>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cstring>
#include <array>
#include <cmath>
#include <cstddef>

namespace lantern::game {

namespace {

// Mirror of lantern/game_world.glsl's WorldFrame struct (std140: vec4 and mat4 members only). The
// shader reads it as frames[slot] of a two-frame block with `slot` a push constant, always 0:
// that keeps lavapipe from compiling a shader variant per frame (game_world.glsl says why).
struct alignas(16) WorldFrame {
    glm::mat4 view_projection{1.0f};
    glm::vec4 camera{0.0f};     // xyz camera position
    glm::vec4 window{0.0f};     // min x, min z, width, height (texels)
    glm::vec4 config{0.0f};     // resolution, tone map, white point, directional angle scale
    glm::vec4 options{0.0f};    // wall lighting, AO on walls (1/0)
    glm::ivec4 grid{0};         // wall grid width, height, origin x, origin z
    glm::ivec4 grid_phase{0};   // phase x, z
    glm::ivec4 gi{0};           // pitch, presence bits, sun count, GI on
    glm::ivec4 art{0};          // posterize levels, dither, palette colours, pattern
    glm::vec4 art_params{0.0f}; // dither amplitude
    glm::vec4 bounce{1.0f, 0.0f, 1.0f, 0.0f}; // BounceStyle: world self, bleed; characters self, bleed
    glm::ivec4 view_tex{0};     // the GI view's texture: width, height, pitch
    glm::vec4 view_params{0.0f}; // its texels per world unit
    glm::ivec4 probes{0};       // the live probes: first tile x, z, count x | count z << 16, pitch (0: none)
    std::array<glm::vec4, max_palette_colors> palette{};
    std::array<gi::GpuDirectionalLight, 8> suns{};
};
static_assert(sizeof(WorldFrame) == 64 + 13 * 16 + 16 * 16 + 8 * 48, "WorldFrame mirrors lantern/game_world.glsl");

static_assert(offsetof(BoxInstance, half) == 16 && offsetof(BoxInstance, color) == 32,
              "BoxInstance must match game_world.vert.glsl's three texels per box");

constexpr int face_count = 5;                 // +x, -x, +z, -z, top (shader FACE)
constexpr int face_top_index = 4;
// The shader's WALL_LOOKUP: what the shading library's wall test answers for a draw.
enum Lookup : int { lookup_grid = 0, lookup_air = 1, lookup_wall = 2, lookup_count = 3 };

// The draws of a frame, in order: tops (wall boxes' first: their light is one value per face,
// computed by the vertex stage; then props and glow), the sides of wall boxes, other sides, the
// texel_lit boxes by face (their own pipelines: only they pay for the texel lookups), the
// ground last (what stands on it hides it before it is shaded).
struct DrawGroup {
    int face;
    Lookup lookup;
    bool texel = false;
};
constexpr std::array<DrawGroup, 16> draw_groups = {{
    {4, lookup_wall}, {4, lookup_grid},
    {0, lookup_wall}, {1, lookup_wall}, {2, lookup_wall}, {3, lookup_wall},
    {0, lookup_grid}, {1, lookup_grid}, {2, lookup_grid}, {3, lookup_grid},
    {0, lookup_grid, true}, {1, lookup_grid, true}, {2, lookup_grid, true}, {3, lookup_grid, true}, {4, lookup_grid, true},
    {4, lookup_air},
}};
constexpr int texel_group_first = 10, ground_group = 15;
// The group of a visible face of a box of `material` (texel_lit only when the view has texel light).
int draw_group(int face, int material) {
    if (material == int(Material::texel_lit)) return texel_group_first + face;
    if (face == face_top_index)
        return material == int(Material::ground) ? ground_group : material == int(Material::wall) ? 0 : 1;
    return (material == int(Material::wall) ? 2 : 6) + face;
}
constexpr std::uint32_t binding_frame = 0, binding_walls = 1, binding_first_texture = 2;
constexpr int gi_texture_count = 16; // GI_DIRECT ... GI_WALL_UPPER + 3 (shading.glsl ids)
constexpr std::uint32_t binding_boxes = binding_first_texture + gi_texture_count; // the faces' boxes
constexpr std::uint32_t binding_view = binding_boxes + 1;                           // the GI view's texture
constexpr std::uint32_t binding_texel_lit = binding_view + 1;      // the per-texel light (storage)
constexpr std::uint32_t binding_texel_surfaces = binding_view + 2; // its texels' world positions
constexpr std::uint32_t binding_texel_albedo = binding_view + 3;   // its texels' albedo
constexpr std::uint32_t binding_probes = binding_view + 4;         // the GI's live probes (gi::Tex::probes)
constexpr VkDeviceSize initial_box_capacity = 4096;

// Shading-library texture ids (shading.glsl GI_*) in binding order.
constexpr std::array<gi::vk::Tex, gi_texture_count> gi_textures = {
    gi::vk::Tex::direct,           gi::vk::Tex::indirect,         gi::vk::Tex::ao,
    gi::vk::Tex::shadow,           gi::vk::Tex::wall_direct_px,   gi::vk::Tex::wall_direct_nx,
    gi::vk::Tex::wall_direct_pz,   gi::vk::Tex::wall_direct_nz,   gi::vk::Tex::wall_indirect_px,
    gi::vk::Tex::wall_indirect_nx, gi::vk::Tex::wall_indirect_pz, gi::vk::Tex::wall_indirect_nz,
    gi::vk::Tex::wall_upper_px,    gi::vk::Tex::wall_upper_nx,    gi::vk::Tex::wall_upper_pz,
    gi::vk::Tex::wall_upper_nz,
};

glm::vec3 hex(std::uint32_t rgb) {
    return glm::vec3(float((rgb >> 16) & 0xff), float((rgb >> 8) & 0xff), float(rgb & 0xff)) / 255.0f;
}

std::vector<Palette> make_palettes() {
    auto of = [](const char* name, std::initializer_list<std::uint32_t> colors) {
        Palette p{name, {}};
        for (std::uint32_t c : colors) p.colors.push_back(hex(c));
        return p;
    };
    static_assert(palette_count == 5, "the palettes below are palette_names (settings.hpp), in order");
    return {
        Palette{palette_names[0], {}},
        of(palette_names[1], {0x0d0907, 0x1f1510, 0x3a261a, 0x5c3a24, 0x83552f, 0xb0773a, 0xd9a24e, 0xf5d58a, 0xfff3d0,
                    0x1b2a3a, 0x3d6480, 0x8fc3d9}),
        of(palette_names[2], {0x0f380f, 0x306230, 0x8bac0f, 0x9bbc0f}),
        of(palette_names[3], {0x000000, 0x1d2b53, 0x7e2553, 0x008751, 0xab5236, 0x5f574f, 0xc2c3c7, 0xfff1e8, 0xff004d,
                    0xffa300, 0xffec27, 0x00e436, 0x29adff, 0x83769c, 0xff77a8, 0xffccaa}),
        of(palette_names[4], {0x0b0b1a, 0x241a3d, 0x4a2c5e, 0x7d3c6b, 0xc0566b, 0xf08a5d, 0xf9c784, 0x3b5b8c}),
    };
}

// The shader's GI_VIEW modes (lantern/game_world.glsl).
enum ViewMode : int {
    view_off = 0,
    view_light = 1,
    view_distance = 2,
    view_direction = 3,
    view_nearest = 4,
    view_bricks = 5,
    view_modes = 6
};

// What a GI view draws: its texture, the shader's mode for it, and the texture's texels per
// world unit (window textures: the resolution; the radiosity grid's: resolution / scale).
struct ViewSource {
    gi::Tex tex;
    ViewMode mode;
    float texels_per_unit;
};
std::optional<ViewSource> view_source(GiDebugView v, const gi::FrameInputs& in) {
    const float window_tpu = float(in.window.resolution);
    const float grid_tpu = gi::radiosity_grid(in).texels_per_unit;
    switch (v) {
    case GiDebugView::direct: return ViewSource{gi::Tex::direct, view_light, window_tpu};
    case GiDebugView::indirect: return ViewSource{gi::Tex::indirect, view_light, window_tpu};
    case GiDebugView::light_image: return ViewSource{gi::Tex::radiosity_light, view_light, grid_tpu};
    case GiDebugView::radiosity: return ViewSource{gi::Tex::radiosity, view_light, grid_tpu};
    case GiDebugView::distance: return ViewSource{gi::Tex::distance_field, view_distance, grid_tpu};
    case GiDebugView::direction: return ViewSource{gi::Tex::distance_field, view_direction, grid_tpu};
    case GiDebugView::jump_flood: return ViewSource{gi::jump_flood_result(in), view_nearest, grid_tpu};
    case GiDebugView::baked: return ViewSource{gi::Tex::baked_view, view_light, window_tpu};
    case GiDebugView::bricks: return ViewSource{gi::Tex::baked_view, view_bricks, window_tpu};
    default: return std::nullopt;
    }
}

gpu::GraphicsPipelineDesc pipeline_desc(const render::RenderTarget& target, int face, bool gi, bool art, int lookup,
                                        int view, bool xray = false, bool texel = false, bool styled = false) {
    gpu::GraphicsPipelineDesc p;
    p.vertex_spirv = lantern_game_shaders_spirv("game_world.vert");
    p.fragment_spirv = lantern_game_shaders_spirv("game_world.frag");
    // No vertex input: the vertex shader pulls its face's box from the box texel buffer by
    // gl_VertexIndex / 6, one plain draw per face group. (Measured against per-instance vertex
    // attributes on lavapipe: the same frame time; pulling keeps the mesh in the shader.)
    p.bindings.push_back(gpu::BindingType::uniform_buffer); // WorldFrames
    p.push_constant_size = sizeof(std::int32_t);            // WorldSlot
    for (std::uint32_t i = binding_walls; i <= binding_view; ++i)
        p.bindings.push_back(gpu::BindingType::uniform_texel_buffer);
    for (std::uint32_t i = binding_texel_lit; i <= binding_texel_albedo; ++i)
        p.bindings.push_back(gpu::BindingType::storage_buffer);
    p.bindings.push_back(gpu::BindingType::uniform_texel_buffer); // binding_probes
    p.specialization = {{0, std::uint32_t(face)},
                        {1, gi ? 1u : 0u},
                        {2, art ? 1u : 0u},
                        {3, std::uint32_t(lookup)},
                        {4, std::uint32_t(view)},
                        {5, xray ? 1u : 0u},
                        {6, texel ? 1u : 0u},
                        {7, styled ? 1u : 0u}};
    p.cull = VK_CULL_MODE_NONE; // faces turned away are never listed
    // The x-ray pass draws where the depth buffer holds something nearer, and keeps it.
    p.depth = xray ? gpu::DepthState{true, false, VK_COMPARE_OP_GREATER} : gpu::DepthState{true, true, VK_COMPARE_OP_LESS};
    p.color_format = target.color_format();
    p.depth_format = target.depth_format();
    p.name = "game world";
    return p;
}

constexpr glm::vec3 face_normal[face_count] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {0, 1, 0}};

// The six planes of a Vulkan (0 <= z <= w) clip volume, as a * x + b * y + c * z + d >= 0.
std::array<glm::vec4, 6> frustum_planes(const glm::mat4& m) {
    auto row = [&](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    return {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(2), row(3) - row(2)};
}

bool outside(const std::array<glm::vec4, 6>& planes, glm::vec3 lo, glm::vec3 hi) {
    for (const glm::vec4& p : planes) {
        const glm::vec3 v(p.x > 0.0f ? hi.x : lo.x, p.y > 0.0f ? hi.y : lo.y, p.z > 0.0f ? hi.z : lo.z);
        if (p.x * v.x + p.y * v.y + p.z * v.z + p.w < 0.0f) return true;
    }
    return false;
}

} // namespace

BoxInstance ground_box(glm::vec2 min, glm::vec2 max, glm::vec3 color) {
    BoxInstance b;
    b.center = glm::vec3((min.x + max.x) * 0.5f, 0.0f, (min.y + max.y) * 0.5f);
    b.material = float(int(Material::ground));
    b.half = glm::vec3(std::abs(max.x - min.x) * 0.5f, 0.0f, std::abs(max.y - min.y) * 0.5f);
    b.face_mask = float(face_top);
    b.color = color;
    b.emissive = 0.0f;
    return b;
}

void append_wall_boxes(DrawList& list, const IsWall& is_wall, glm::ivec2 min_tile, glm::ivec2 max_tile,
                       float height, glm::vec3 color) {
    for (int z = min_tile.y; z < max_tile.y; ++z)
        for (int x = min_tile.x; x < max_tile.x; ++x) {
            if (!is_wall(x, z)) continue;
            int mask = face_top;
            if (!is_wall(x + 1, z)) mask |= face_pos_x;
            if (!is_wall(x - 1, z)) mask |= face_neg_x;
            if (!is_wall(x, z + 1)) mask |= face_pos_z;
            if (!is_wall(x, z - 1)) mask |= face_neg_z;
            BoxInstance b;
            b.center = glm::vec3(float(x) + 0.5f, height * 0.5f, float(z) + 0.5f);
            b.material = float(int(Material::wall));
            b.half = glm::vec3(0.5f, height * 0.5f, 0.5f);
            b.face_mask = float(mask);
            b.color = color;
            b.emissive = 0.0f;
            list.boxes.push_back(b);
        }
}

glm::vec3 reflected_bounce(const BounceStyle& style, glm::vec3 bounce, glm::vec3 albedo) {
    const glm::vec3 chroma = albedo - (albedo.r + albedo.g + albedo.b) / 3.0f;
    const float length = glm::length(chroma);
    if (length > 1e-6f) {
        const glm::vec3 c = chroma / length;
        bounce -= (1.0f - style.self) * std::max(glm::dot(bounce, c), 0.0f) * c;
    }
    return bounce * glm::mix(albedo, glm::vec3(1.0f), style.bleed);
}

glm::vec3 probe_face_light(const ProbeRecord& r, float phi) {
    constexpr float pi = 3.14159265f;
    const glm::vec3 a0(r.c[0]), a1(r.c[1]), b1(r.c[2]), a2(r.c[3]), b2(r.c[4]);
    const glm::vec3 e = a0 / pi + (a1 * std::cos(phi) + b1 * std::sin(phi)) * 0.5f +
                        (a2 * std::cos(2.0f * phi) + b2 * std::sin(2.0f * phi)) * (2.0f / (3.0f * pi));
    return glm::max(pi * e, glm::vec3(0.0f)) - a0;
}

std::span<const Palette> builtin_palettes() {
    static const std::vector<Palette> palettes = make_palettes();
    return palettes;
}

struct WorldRenderer::Impl {
    gpu::Device* device = nullptr;
    render::RenderTarget target;
    // By face, wall lookup, GI on, art on, GI view mode, texel lit, bounce styled (specialisation
    // constants), created on first use.
    std::array<gpu::GraphicsPipeline, face_count * lookup_count * 4 * view_modes * 2 * 2> pipelines;
    std::array<gpu::GraphicsPipeline, face_count> xray_pipelines; // by face, created on first use
    std::array<std::vector<BoxInstance>, face_count> xray_faces;   // this frame's (reused)
    render::StreamBuffer instances;
    gpu::BufferView instance_texels; // RGBA32F, three texels per box
    render::StreamBuffer frame;
    gpu::Buffer dummy;             // absent GI textures and walls read this (never, in fact)
    gpu::BufferView dummy_texels;  // RGBA16F
    gpu::BufferView dummy_walls;   // R8_UINT
    gpu::Buffer dummy_storage;     // the texel bindings without texel light
    // This frame's faces by draw group (reused): DrawList::boxes', and DrawList::late's (drawn
    // after the x-ray pass).
    std::array<std::vector<BoxInstance>, draw_groups.size()> faces, late_faces;
    std::vector<BoxInstance> upload;
    std::size_t faces_drawn = 0;
    GiDebugView view_drawn = GiDebugView::lit;

    void create_instances(VkDeviceSize capacity) {
        instances = render::StreamBuffer::create(*device, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, capacity,
                                                 "game world boxes");
        instance_texels = device->create_buffer_view(instances.buffer(), VK_FORMAT_R32G32B32A32_SFLOAT, 0,
                                                     VK_WHOLE_SIZE, "game world box texels");
    }

    const gpu::GraphicsPipeline& pipeline(int face, Lookup lookup, bool gi, bool art, ViewMode view, bool texel,
                                          bool styled = false) {
        if (!gi || view != view_off) lookup = lookup_grid, styled = false; // compiled out anyway
        if (view != view_off) art = false, texel = false;                  // GI views show the GI texture only
        const int key =
            face + face_count * (int(lookup) + lookup_count * ((gi ? 1 : 0) + (art ? 2 : 0) +
                                                               4 * (int(view) + view_modes * ((texel ? 1 : 0) + (styled ? 2 : 0)))));
        gpu::GraphicsPipeline& p = pipelines[std::size_t(key)];
        if (!p) p = device->create_graphics_pipeline(pipeline_desc(target, face, gi, art, lookup, view, false, texel, styled));
        return p;
    }
    const gpu::GraphicsPipeline& xray_pipeline(int face) {
        gpu::GraphicsPipeline& p = xray_pipelines[std::size_t(face)];
        if (!p) p = device->create_graphics_pipeline(pipeline_desc(target, face, false, false, lookup_grid, view_off, true));
        return p;
    }
};

WorldRenderer::WorldRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
WorldRenderer::~WorldRenderer() = default;

render::RenderTarget& WorldRenderer::target() { return impl_->target; }

Result<void> WorldRenderer::resize(glm::ivec2 size) {
    if (size.x <= 0 || size.y <= 0) return Error{"game world renderer: empty target size", 1};
    const VkExtent2D now = impl_->target.extent();
    if (int(now.width) == size.x && int(now.height) == size.y) return {};
    impl_->target = render::RenderTarget::create(
        *impl_->device, {std::uint32_t(size.x), std::uint32_t(size.y), VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_D32_SFLOAT,
                         "game world"});
    return {};
}
std::size_t WorldRenderer::faces_drawn() const { return impl_->faces_drawn; }
GiDebugView WorldRenderer::gi_view_drawn() const { return impl_->view_drawn; }

Result<std::unique_ptr<WorldRenderer>> WorldRenderer::create(gpu::Device& device, glm::ivec2 size) {
    if (!device.capabilities().graphics)
        return Error{"game world renderer: the Vulkan device was created without raster support "
                     "(DeviceOptions::graphics)", 1};
    if (size.x <= 0 || size.y <= 0) return Error{"game world renderer: empty target size", 1};
    auto impl = std::make_unique<Impl>();
    impl->device = &device;
    impl->target = render::RenderTarget::create(
        device, {std::uint32_t(size.x), std::uint32_t(size.y), VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_D32_SFLOAT,
                 "game world"});
    for (const DrawGroup& g : draw_groups)
        if (!g.texel) impl->pipeline(g.face, g.lookup, true, false, view_off, false); // the usual frame
    impl->create_instances(initial_box_capacity * sizeof(BoxInstance));
    impl->frame = render::StreamBuffer::create(device, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, 2 * sizeof(WorldFrame),
                                               "game world frame");
    impl->dummy = device.create_buffer(
        {16, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, gpu::MemoryKind::upload, "game world dummy"});
    impl->dummy_texels = device.create_buffer_view(impl->dummy, VK_FORMAT_R16G16B16A16_SFLOAT, 0, VK_WHOLE_SIZE,
                                                   "game world dummy texels");
    impl->dummy_walls =
        device.create_buffer_view(impl->dummy, VK_FORMAT_R8_UINT, 0, VK_WHOLE_SIZE, "game world dummy walls");
    const std::array<std::byte, 16> zeros{};
    device.upload(impl->dummy, zeros); // host-visible: a memcpy, no submission
    impl->dummy_storage =
        device.create_buffer({16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::upload, "game world dummy storage"});
    device.upload(impl->dummy_storage, zeros);
    return std::unique_ptr<WorldRenderer>(new WorldRenderer(std::move(impl)));
}

glm::mat4 WorldRenderer::view_projection(const scene::PerspectiveCamera& c) {
    // The basis of game::camera_ray and gi::visible_area: forward, right = forward x up_hint,
    // up = right x forward, which is exactly glm::lookAtRH's.
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    const glm::vec3 up_hint = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::mat4 view = glm::lookAtRH(c.position, c.target, up_hint);
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(c.fov_deg), c.aspect, near_plane, far_plane);
    projection[1][1] = -projection[1][1]; // Vulkan: framebuffer y grows downwards
    return projection * view;
}

void WorldRenderer::record(gpu::CommandList& cmd, const WorldView& view, const DrawList& list) {
    Impl& m = *impl_;

    // The GI passes (compute) and the wall/light uploads (transfer) recorded before this are
    // read by the vertex stage (wall tops) and the fragment stage.
    cmd.memory_barrier(VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                       VK_ACCESS_SHADER_READ_BIT);

    // Faces: outside the view, not in the mask or turned away from the camera are left out;
    // the others are listed by draw group (one pipeline each).
    const glm::mat4 view_projection_matrix = view_projection(view.camera);
    const std::array<glm::vec4, 6> planes = frustum_planes(view_projection_matrix);
    const bool texel_on = view.texel_lit && view.texel_surfaces && view.texel_albedo && !view.texel_records.empty() &&
                          (!view.gi || view.gi_view == GiDebugView::lit);
    const auto list_faces = [&](const std::vector<BoxInstance>& boxes, auto& groups) {
        for (auto& f : groups) f.clear();
        for (BoxInstance b : boxes) {
            if (int(b.material) == int(Material::texel_lit) &&
                (!texel_on || b.emissive < 0.0f || std::size_t(b.emissive) >= view.texel_records.size())) {
                b.material = float(int(Material::prop)); // no texel light for it: a plain prop
                b.emissive = 0.0f;
            }
            const glm::vec3 half = glm::max(b.half, glm::vec3(0.0f));
            if (outside(planes, b.center - half, b.center + half)) continue;
            const int mask = int(b.face_mask + 0.5f);
            for (int face = 0; face < face_count; ++face) {
                if (!((mask >> face) & 1)) continue;
                const glm::vec3 n = face_normal[face];
                if (glm::dot(view.camera.position - (b.center + half * n), n) <= 0.0f) continue;
                groups[std::size_t(draw_group(face, int(b.material)))].push_back(b);
            }
        }
    };
    list_faces(list.boxes, m.faces);
    list_faces(list.late, m.late_faces);
    m.upload.clear();
    for (const auto& f : m.faces) m.upload.insert(m.upload.end(), f.rbegin(), f.rend());
    const auto late_first = std::uint32_t(m.upload.size());
    for (const auto& f : m.late_faces) m.upload.insert(m.upload.end(), f.rbegin(), f.rend());
    m.faces_drawn = m.upload.size();
    // The probe records after the faces, two instances each; a lit_probes face points at its
    // record's first texel.
    for (BoxInstance& b : m.upload)
        if (int(b.material) == int(Material::lit_probes)) {
            if (list.probes.empty()) { // no record: a plain prop
                b.material = float(int(Material::prop));
                b.emissive = 0.0f;
                continue;
            }
            const std::size_t r = std::min(std::size_t(std::max(0.0f, b.emissive)), list.probes.size() - 1);
            b.emissive = float(3 * (m.faces_drawn + 2 * r));
        }
    for (const ProbeRecord& r : list.probes) {
        BoxInstance two[2];
        std::memcpy(static_cast<void*>(two), &r, sizeof(r));
        m.upload.insert(m.upload.end(), two, two + 2);
    }
    // The texel records after the probe records, the same way; a texel_lit face points at its
    // record's first texel (its index was checked above).
    if (texel_on) {
        const std::size_t records_first = m.upload.size();
        for (BoxInstance& b : m.upload)
            if (int(b.material) == int(Material::texel_lit)) b.emissive = float(3 * (records_first + 2 * std::size_t(b.emissive)));
        for (TexelRecord r : view.texel_records) {
            // Its probe record's index becomes 1 + the record's first texel (0: none).
            const int probe = int(r.texture.z + 0.5f) - 1;
            r.texture.z = probe >= 0 && std::size_t(probe) < list.probes.size()
                              ? float(3 * (m.faces_drawn + 2 * std::size_t(probe)) + 1)
                              : 0.0f;
            BoxInstance two[2];
            std::memcpy(static_cast<void*>(two), &r, sizeof(r));
            m.upload.insert(m.upload.end(), two, two + 2);
        }
    }
    // The x-ray faces last, by face (one pipeline each), as glow (the vertex stage reads no
    // probe record for them).
    for (auto& f : m.xray_faces) f.clear();
    for (BoxInstance b : list.xray) {
        const glm::vec3 half = glm::max(b.half, glm::vec3(0.0f));
        if (outside(planes, b.center - half, b.center + half)) continue;
        b.material = float(int(Material::glow));
        const int mask = int(b.face_mask + 0.5f);
        for (int face = 0; face < face_count; ++face)
            if (((mask >> face) & 1) && glm::dot(view.camera.position - (b.center + half * face_normal[face]), face_normal[face]) > 0.0f)
                m.xray_faces[std::size_t(face)].push_back(b);
    }
    const auto xray_first = std::uint32_t(m.upload.size());
    for (const auto& f : m.xray_faces) m.upload.insert(m.upload.end(), f.begin(), f.end());
    const VkDeviceSize bytes = VkDeviceSize(m.upload.size()) * sizeof(BoxInstance);
    if (bytes > m.instances.capacity()) {
        VkDeviceSize capacity = m.instances.capacity();
        while (capacity < bytes) capacity *= 2;
        // The old buffer is destroyed deferred: earlier frames still reading it are safe.
        m.create_instances(capacity);
    }
    if (bytes) m.instances.write(cmd, std::as_bytes(std::span<const BoxInstance>(m.upload)));

    // Frame constants and GI bindings.
    WorldFrame f;
    f.view_projection = view_projection_matrix;
    f.camera = glm::vec4(view.camera.position, 1.0f);
    gpu::DescriptorWrites writes;
    writes.uniform_buffer(binding_frame, m.frame.buffer());
    ViewMode view_mode = view_off;
    const bool gi_on = view.gi && view.renderer;
    scene::GiSettings no_gi;
    const scene::GiSettings& settings = gi_on ? view.gi->settings : no_gi;
    f.config = glm::vec4(0.0f, float(int(settings.tone_map)), settings.white_point, settings.directional_angle_scale);
    f.options = glm::vec4(settings.wall_lighting ? 1.0f : 0.0f, settings.ao.walls ? 1.0f : 0.0f, 0.0f, 0.0f);
    if (gi_on) {
        const gi::FrameInputs& in = *view.gi;
        const gi::GiWindow& w = in.window;
        const gi::vk::Renderer& r = *view.renderer;
        f.window = glm::vec4(w.view.min_x, w.view.min_z, float(w.width), float(w.height));
        f.config.x = float(w.resolution);
        f.grid = glm::ivec4(in.walls.width, in.walls.height, in.walls.origin.x, in.walls.origin.y);
        f.grid_phase = glm::ivec4(in.walls.phase, 0, 0);
        int present = 0, pitch = 0;
        for (int i = 0; i < gi_texture_count; ++i) {
            const gi::vk::Tex t = gi_textures[std::size_t(i)];
            const gpu::BufferView* v = r.view(t);
            if (v) {
                LANTERN_ASSERT(r.size(t) == glm::ivec2(w.width, w.height),
                               "game world renderer: the GI renderer's textures are not this window's");
                LANTERN_ASSERT(pitch == 0 || r.pitch(t) == pitch, "game world renderer: GI textures of different pitch");
                pitch = r.pitch(t);
                present |= 1 << i;
            }
            writes.uniform_texel_buffer(binding_first_texture + std::uint32_t(i), v ? *v : m.dummy_texels);
        }
        const int suns = int(std::min(in.directional_lights.size(), f.suns.size()));
        for (int i = 0; i < suns; ++i) f.suns[std::size_t(i)] = in.directional_lights[std::size_t(i)];
        f.gi = glm::ivec4(pitch, present, suns, 1);
        const bool walls = bool(r.walls_view());
        writes.uniform_texel_buffer(binding_walls, walls ? r.walls_view() : m.dummy_walls);
        if (!walls) f.grid = glm::ivec4(0); // nothing uploaded: every tile is air
        // The live probes, when this frame captured them.
        if (const gpu::BufferView* probes = r.view(gi::vk::Tex::probes)) {
            const gi::ProbeGrid g = gi::probe_grid(in);
            f.probes = glm::ivec4(g.first_tile, g.count.x | (g.count.y << 16), r.pitch(gi::vk::Tex::probes));
            writes.uniform_texel_buffer(binding_probes, *probes);
        } else {
            writes.uniform_texel_buffer(binding_probes, m.dummy_texels);
        }
        // The GI view: its texture when this frame has it, else the lit scene.
        if (const auto source = view_source(view.gi_view, in); source && r.view(source->tex)) {
            const glm::ivec2 size = r.size(source->tex);
            f.view_tex = glm::ivec4(size, r.pitch(source->tex), 0);
            f.view_params = glm::vec4(source->texels_per_unit, 0.0f, 0.0f, 0.0f);
            writes.uniform_texel_buffer(binding_view, *r.view(source->tex));
            view_mode = source->mode;
        } else {
            writes.uniform_texel_buffer(binding_view, m.dummy_texels);
        }
    } else {
        writes.uniform_texel_buffer(binding_view, m.dummy_texels);
        writes.uniform_texel_buffer(binding_walls, m.dummy_walls);
        writes.uniform_texel_buffer(binding_probes, m.dummy_texels);
        for (int i = 0; i < gi_texture_count; ++i)
            writes.uniform_texel_buffer(binding_first_texture + std::uint32_t(i), m.dummy_texels);
    }

    // Art controls.
    const ArtSettings& art = view.art;
    const int levels = art.posterize > 0 ? std::clamp(art.posterize, 2, 64) : 0;
    const std::span<const Palette> palettes = builtin_palettes();
    const Palette* palette = art.palette > 0 && std::size_t(art.palette) < palettes.size()
                                 ? &palettes[std::size_t(art.palette)]
                                 : nullptr;
    const int colors = palette ? int(std::min<std::size_t>(palette->colors.size(), max_palette_colors)) : 0;
    for (int i = 0; i < colors; ++i) f.palette[std::size_t(i)] = glm::vec4(palette->colors[std::size_t(i)], 1.0f);
    f.art = glm::ivec4(levels, art.dither ? 1 : 0, colors, art.texture_pattern ? 1 : 0);
    const float amplitude = levels ? 1.0f / float(levels - 1)
                            : colors ? 0.5f / std::sqrt(float(colors))
                                     : 1.0f / 255.0f;
    f.art_params = glm::vec4(amplitude, 0.0f, 0.0f, 0.0f);
    f.bounce = glm::vec4(view.world_bounce.self, view.world_bounce.bleed, view.character_bounce.self,
                         view.character_bounce.bleed);
    m.frame.write(cmd, std::as_bytes(std::span<const WorldFrame>(&f, 1)));
    writes.uniform_texel_buffer(binding_boxes, m.instance_texels);
    writes.storage_buffer(binding_texel_lit, texel_on ? *view.texel_lit : m.dummy_storage);
    writes.storage_buffer(binding_texel_surfaces, texel_on ? *view.texel_surfaces : m.dummy_storage);
    writes.storage_buffer(binding_texel_albedo, texel_on ? *view.texel_albedo : m.dummy_storage);

    const bool art_on = levels || art.dither || colors;
    const bool styled = view.world_bounce != BounceStyle{} || view.character_bounce != BounceStyle{};
    m.view_drawn = view_mode == view_off ? GiDebugView::lit : view.gi_view;
    m.target.begin(cmd, {{0.0f, 0.0f, 0.0f, 1.0f}});
    bool pushed = false;
    // Descriptors once: every pipeline here has the same layout, so they stay bound across
    // the binds. (Each push cost lavapipe about 1 ms with the GI texel buffers in it, 10 ms a
    // frame for the 10 groups.)
    const auto push_once = [&] {
        if (pushed) return;
        cmd.push_descriptors(writes);
        cmd.push_constants(std::int32_t{0}); // WorldSlot: frames[0]
        pushed = true;
    };
    const auto draw_groups_of = [&](const auto& groups, std::uint32_t first) {
        for (std::size_t d = 0; d < groups.size(); ++d) {
            const auto count = std::uint32_t(groups[d].size());
            if (count) {
                cmd.bind(m.pipeline(draw_groups[d].face, draw_groups[d].lookup, gi_on, art_on, view_mode,
                                    draw_groups[d].texel, styled));
                push_once();
                cmd.draw(6 * count, 1, 6 * first, 0);
            }
            first += count;
        }
    };
    draw_groups_of(m.faces, 0);
    // The x-ray pass after the world: its depth buffer is complete, and holds none of the
    // late boxes (the player's own parts), which are drawn last.
    std::uint32_t first = xray_first;
    for (int face = 0; face < face_count; ++face) {
        const auto count = std::uint32_t(m.xray_faces[std::size_t(face)].size());
        if (!count) continue;
        cmd.bind(m.xray_pipeline(face));
        push_once();
        cmd.draw(6 * count, 1, 6 * first, 0);
        first += count;
    }
    draw_groups_of(m.late_faces, late_first);
    m.target.end(cmd);

}

} // namespace lantern::game
