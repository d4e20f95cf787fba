// The game's world renderer on real Vulkan (lavapipe in CI), validation on (any message fails
// the test): lighting against the C++ shading library on the GPU's own GI textures, the
// projection against game::camera_ray, depth, face masks, glow, frames without GI, the art
// controls. Skipped, and reported, without a device (failed under LANTERN_REQUIRE_GPU=1). The
// GPU time of a typical cave view is measured by benchmarks/world_pass_bench.cpp.
#include "lantern/game/world_renderer.hpp"
#include "lantern/bake/probes.hpp"

#include "lantern/game/gameplay.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/gi/probes.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/buffer.hpp"
#include "lantern/texel/texel.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace lantern;
using game::BoxInstance;
using game::DrawList;
using game::Material;
using game::WorldView;

constexpr glm::ivec2 target_size{480, 270};

// ---- shared GPU objects (created after the shared Device, so destroyed before it)

struct Shared {
    std::unique_ptr<game::WorldRenderer> world;
    std::unique_ptr<gi::vk::Renderer> gi;
};

Shared& shared(gpu::Device& device) {
    static Shared s = [&] {
        Shared out;
        auto world = game::WorldRenderer::create(device, target_size);
        EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message);
        if (world.ok()) out.world = std::move(world).value();
        auto gi = gi::vk::Renderer::create(device);
        EXPECT_TRUE(gi.ok()) << (gi.ok() ? "" : gi.error().message);
        if (gi.ok()) out.gi = std::move(gi).value();
        return out;
    }();
    return s;
}

// ---- scenes

// A GI frame: the scene (which the inputs point into: keep it where it is), its window,
// inputs and plan.
struct GiFrame {
    scene::Scene scene;
    gi::FrameInputs in;
    gi::PassPlan plan;
};

std::unique_ptr<GiFrame> make_gi_frame(scene::Scene s, const scene::PerspectiveCamera& camera) {
    auto f = std::make_unique<GiFrame>();
    f->scene = std::move(s);
    f->scene.view = camera;
    std::string why;
    auto window = gi::compute_window(f->scene.view, f->scene.gi, &why);
    EXPECT_TRUE(window) << why;
    if (!window) return nullptr;
    f->in = gi::gather_frame_inputs(f->scene, *window);
    f->plan = gi::plan_passes(f->in, false);
    return f;
}

scene::WallGrid grid_from_rows(const std::vector<std::string>& rows) {
    scene::WallGrid g;
    g.height = int(rows.size());
    g.width = int(rows[0].size());
    g.cells.resize(std::size_t(g.width) * std::size_t(g.height));
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) g.cells[std::size_t(c + r * g.width)] = rows[std::size_t(r)][std::size_t(c)] == '#';
    return g;
}

scene::PerspectiveCamera follow(glm::vec2 player) { return game::follow_camera({player.x, 0.0f, player.y}, game::CameraRig{}); }

// Walls, two point lights, an emissive and a sun, seen by the game's camera.
std::unique_ptr<GiFrame> lit_room_frame(scene::GiMethod method = scene::GiMethod::heat) {
    scene::Scene s;
    s.gi.method = method;
    // 28 x 20 tiles, row r is z = r. The camera looks towards -z from z + 9: rows near 19 are
    // at the bottom of the screen, so the +z faces of walls show.
    s.walls = grid_from_rows({
        "############################",
        "#..........................#",
        "#..........................#",
        "#....####..........#.......#",
        "#....#.............#.......#",
        "#....#......##.....#.......#",
        "#...........##.............#",
        "#..........................#",
        "#.........#................#",
        "#.........#.......####.....#",
        "#.........#................#",
        "#..###.....................#",
        "#..........................#",
        "#.............#............#",
        "#.............#.....##.....#",
        "#..........................#",
        "#...#######................#",
        "#..........................#",
        "#..........................#",
        "############################",
    });
    s.wall_height = 1.5f;
    s.gi.resolution = 4;
    s.gi.padding = 1.1f;
    s.gi.heat_rounds = 12;
    s.point_lights.push_back({{8.5f, 7.5f}, 1.0f, {1.0f, 0.7f, 0.4f}, 2.5f, 10.0f});
    s.point_lights.push_back({{20.5f, 12.2f}, 1.0f, {0.4f, 0.6f, 1.0f}, 2.0f, 9.0f});
    s.emissive_lights.push_back({{15.5f, 16.5f}, {0.3f, 1.0f, 0.5f}, 1.5f, 5.0f});
    scene::DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.5f, -0.7f, -0.4f));
    sun.color = {1.0f, 0.95f, 0.85f};
    sun.intensity = 0.25f;
    s.directional_lights.push_back(sun);
    return make_gi_frame(std::move(s), follow({14.0f, 10.0f}));
}

const glm::vec3 ground_albedo{0.75f, 0.7f, 0.62f};
const glm::vec3 wall_albedo{0.6f, 0.63f, 0.72f};

DrawList world_list(const GiFrame& f, bool props = true) {
    DrawList list;
    const gi::CameraView& v = f.in.window.view;
    list.boxes.push_back(game::ground_box({v.min_x - 8.0f, v.min_z - 8.0f}, {v.min_x + v.width + 8.0f, v.min_z + v.height + 8.0f},
                                          ground_albedo));
    const gi::WallView walls = f.in.walls;
    game::append_wall_boxes(list, [&](int x, int z) { return walls.is_wall(x, z); }, walls.origin - 1,
                            walls.origin + glm::ivec2(walls.width, walls.height) + 1, f.in.wall_height, wall_albedo);
    if (props) {
        BoxInstance prop; // a lit, faintly emissive crate in the open
        prop.center = {16.5f, 0.4f, 11.5f};
        prop.half = {0.4f, 0.4f, 0.4f};
        prop.material = float(int(Material::prop));
        prop.color = {0.5f, 0.8f, 0.6f};
        prop.emissive = 0.15f;
        list.boxes.push_back(prop);
        BoxInstance flame; // unlit glow
        flame.center = {8.5f, 0.3f, 12.5f};
        flame.half = {0.2f, 0.3f, 0.2f};
        flame.material = float(int(Material::glow));
        flame.color = {1.0f, 0.6f, 0.2f};
        flame.emissive = 1.5f;
        list.boxes.push_back(flame);
    }
    return list;
}

// ---- CPU side

struct Hit {
    int box = -1;
    int face = -1; // 0 +x, 1 -x, 2 +z, 3 -z, 4 top; 5 a face that cannot be seen (bottom)
    float t = 0.0f;
};

// The nearest box the ray enters (slab test).
Hit trace(const game::Ray& ray, const DrawList& list) {
    Hit best;
    best.t = 1e30f;
    for (std::size_t i = 0; i < list.boxes.size(); ++i) {
        const BoxInstance& b = list.boxes[i];
        const glm::vec3 lo = b.center - b.half, hi = b.center + b.half;
        float t_near = -1e30f, t_far = 1e30f;
        int face = -1;
        bool miss = false;
        for (int a = 0; a < 3; ++a) {
            const float o = ray.origin[a], d = ray.direction[a];
            if (std::abs(d) < 1e-12f) {
                if (o < lo[a] || o > hi[a]) miss = true;
                continue;
            }
            float t0 = (lo[a] - o) / d, t1 = (hi[a] - o) / d;
            const bool entering_low = t0 < t1; // enters through the low side (the -axis face)
            if (!entering_low) std::swap(t0, t1);
            if (t0 > t_near) {
                t_near = t0;
                if (a == 0) face = entering_low ? 1 : 0;
                else if (a == 2) face = entering_low ? 3 : 2;
                else face = entering_low ? 5 : 4;
            }
            t_far = std::min(t_far, t1);
        }
        if (miss || t_near > t_far || t_near <= 0.0f || t_near >= best.t) continue;
        best = {int(i), face, t_near};
    }
    return best;
}

constexpr std::array<glm::vec3, 5> face_normals = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1),
                                                   glm::vec3(0, 0, -1), glm::vec3(0, 1, 0)};

glm::vec2 pixel_ndc(int x, int y) {
    return {(float(x) + 0.5f) / float(target_size.x), (float(y) + 0.5f) / float(target_size.y)};
}

std::array<int, 3> srgb8(glm::vec3 linear) {
    return {int(gi::linear_to_srgb8(linear.r)), int(gi::linear_to_srgb8(linear.g)), int(gi::linear_to_srgb8(linear.b))};
}

std::array<int, 3> pixel(const render::Rgba8Image& image, int x, int y) {
    const std::uint8_t* p = image.pixels.data() + (std::size_t(y) * image.width + std::size_t(x)) * 4;
    return {p[0], p[1], p[2]};
}

int max_diff(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// The pixel a world point falls on, through view_projection (y down).
glm::ivec2 project_pixel(const scene::PerspectiveCamera& camera, glm::vec3 p) {
    const glm::vec4 clip = game::WorldRenderer::view_projection(camera) * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int(std::floor((ndc.x * 0.5f + 0.5f) * float(target_size.x))),
            int(std::floor((ndc.y * 0.5f + 0.5f) * float(target_size.y)))};
}

void maybe_write_png(const render::Rgba8Image& image, const std::string& name) {
    // LANTERN_WORLD_PNG_DIR=<dir>: keep the images for a look.
    if (const char* dir = std::getenv("LANTERN_WORLD_PNG_DIR"); dir && *dir) {
        auto ok = render::write_png(std::string(dir) + "/" + name + ".png", image);
        EXPECT_TRUE(ok.ok());
    }
}

// ---- fixture

class WorldRendererTest : public test::RenderTest {
  protected:
    game::WorldRenderer& world() { return *shared(device()).world; }
    // A storage buffer holding `values` (texel light, albedo, surfaces for texel_lit boxes).
    gpu::Buffer vec4_buffer(const std::vector<glm::vec4>& values, const char* name) {
        gpu::Buffer b = device().create_buffer(
            {values.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::upload, name});
        device().upload(b, std::as_bytes(std::span<const glm::vec4>(values)));
        return b;
    }
    gi::vk::Renderer& gi() { return *shared(device()).gi; }

    // A texel_lit crate (texel::box_model at 4 texels per unit) whose every texel is lit with
    // `light` and has albedo `albedo`, all at its centre: its model and buffers.
    struct TexelCrate {
        glm::vec3 center{0.0f}, half{0.0f};
        texel::Model model;
        gpu::Buffer lit, albedo, surfaces;
    };
    TexelCrate texel_crate(glm::vec3 center, glm::vec3 half, float light, float albedo) {
        TexelCrate c{center, half, texel::box_model(center - half, center + half, 4), {}, {}, {}};
        const std::size_t texels = std::size_t(c.model.size) * std::size_t(c.model.size);
        c.lit = vec4_buffer(std::vector<glm::vec4>(texels, glm::vec4(light)), "test texel lit");
        c.albedo = vec4_buffer(std::vector<glm::vec4>(texels, glm::vec4(glm::vec3(albedo), 1.0f)), "test texel albedo");
        c.surfaces = vec4_buffer(std::vector<glm::vec4>(3 * texels, glm::vec4(center, 1.0f)), "test texel surfaces");
        return c;
    }
    // `list` with the crate added (its record's texture.z `probe` and .w `glow`, its box's
    // colour `color`), drawn.
    render::Rgba8Image draw_crate(WorldView view, DrawList list, const TexelCrate& c, float probe, float glow,
                                  glm::vec3 color, const GiFrame* frame) {
        game::TexelRecord record;
        record.texture = glm::vec4(0.0f, float(c.model.size), probe, glow);
        for (std::size_t f = 0; f < 5; ++f) record.faces[f] = glm::vec4(c.model.faces[f]);
        BoxInstance b;
        b.center = c.center;
        b.half = c.half;
        b.material = float(int(Material::texel_lit));
        b.color = color;
        b.emissive = 0.0f;
        list.boxes.push_back(b);
        view.texel_lit = &c.lit;
        view.texel_albedo = &c.albedo;
        view.texel_surfaces = &c.surfaces;
        view.texel_records = std::span<const game::TexelRecord>(&record, 1);
        return draw(view, list, frame);
    }

    // Records the GI of `frame` (when given) and the world in one list, submits, reads back.
    render::Rgba8Image draw(WorldView view, const DrawList& list, const GiFrame* frame) {
        gpu::CommandList cmd = device().begin("world renderer test");
        if (frame) {
            auto ok = gi().prepare(frame->in, frame->plan);
            EXPECT_TRUE(ok.ok()) << (ok.ok() ? "" : ok.error().message);
            gi().upload_walls(cmd, frame->in.walls);
            gi().upload_lights(cmd, frame->in);
            gi().record_plan(cmd, frame->in, frame->plan);
            view.gi = &frame->in;
            view.renderer = &gi();
        }
        world().record(cmd, view, list);
        device().submit(std::move(cmd));
        return world().target().read_back();
    }

    gi::Texture read(gi::vk::Tex t) { return gi().read_back(t); }

    // The GPU's own GI textures of the last frame drawn, as the C++ shading library reads them.
    struct GpuShading {
        std::map<gi::vk::Tex, gi::Texture> textures;
        gi::ShadingInputs in;
    };
    std::unique_ptr<GpuShading> read_shading(const GiFrame& frame) {
        using gi::vk::Tex;
        auto s = std::make_unique<GpuShading>();
        for (Tex t : {Tex::direct, Tex::indirect, Tex::ao, Tex::shadow, Tex::wall_direct_px, Tex::wall_direct_nx,
                      Tex::wall_direct_pz, Tex::wall_direct_nz, Tex::wall_indirect_px, Tex::wall_indirect_nx,
                      Tex::wall_indirect_pz, Tex::wall_indirect_nz}) {
            if (!gi().has(t)) {
                ADD_FAILURE() << "no " << gi::vk::tex_name(t);
                return nullptr;
            }
            s->textures[t] = read(t);
        }
        gi::ShadingInputs& in = s->in;
        in.frame = &frame.in;
        in.direct = &s->textures[Tex::direct];
        in.indirect = &s->textures[Tex::indirect];
        in.ao = &s->textures[Tex::ao];
        in.shadow = &s->textures[Tex::shadow];
        for (int f = 0; f < 4; ++f) {
            in.wall_direct[std::size_t(f)] = &s->textures[Tex(int(Tex::wall_direct_px) + f)];
            in.wall_indirect[std::size_t(f)] = &s->textures[Tex(int(Tex::wall_indirect_px) + f)];
        }
        return s;
    }
};

// Each pixel of `image` against `expected(box, point, normal)` (sRGB8) at the point the
// pixel's centre ray meets. Pixels whose neighbours meet another box or face (geometric
// edges) are skipped. Positions within a hair of a GI texel or tile boundary may land on
// either side on the GPU (interpolation vs. ray hit): the reference is taken at the hit and
// at the hit moved by +-eps along the face, best match counted.
struct PixelComparison {
    int worst = 0, compared = 0, edges = 0, boundary = 0, over = 0;
    double mean = 0.0;
    std::array<int, 3> kinds{}; // lit pixels by SurfaceKind
    glm::ivec2 worst_at{-1};
    std::array<int, 3> worst_gpu{}, worst_ref{};
};

template <typename Expected>
PixelComparison compare_pixels(const render::Rgba8Image& image, const scene::PerspectiveCamera& camera,
                               const DrawList& list, const GiFrame& frame, Expected&& expected) {
    PixelComparison r;
    std::vector<Hit> hits(std::size_t(target_size.x * target_size.y));
    for (int y = 0; y < target_size.y; ++y)
        for (int x = 0; x < target_size.x; ++x)
            hits[std::size_t(y * target_size.x + x)] = trace(game::camera_ray(camera, pixel_ndc(x, y)), list);
    const float eps = 2e-3f;
    double sum = 0.0;
    for (int y = 1; y + 1 < target_size.y; ++y)
        for (int x = 1; x + 1 < target_size.x; ++x) {
            const Hit& h = hits[std::size_t(y * target_size.x + x)];
            if (h.box < 0 || h.face > 4) {
                ++r.edges;
                continue;
            }
            bool edge = false;
            for (glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
                const Hit& o = hits[std::size_t((y + d.y) * target_size.x + x + d.x)];
                edge = edge || o.box != h.box || o.face != h.face;
            }
            if (edge) {
                ++r.edges;
                continue;
            }
            const BoxInstance& b = list.boxes[std::size_t(h.box)];
            EXPECT_TRUE((int(b.face_mask) >> h.face) & 1) << "a ray entered a box through a face not drawn";
            const game::Ray ray = game::camera_ray(camera, pixel_ndc(x, y));
            const glm::vec3 hit = ray.origin + ray.direction * h.t;
            const glm::vec3 n = face_normals[std::size_t(h.face)];
            const std::array<int, 3> gpu = pixel(image, x, y);
            int best = max_diff(gpu, expected(b, hit, n));
            if (best > 2) {
                ++r.boundary;
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dx = -1; dx <= 1; ++dx) {
                        glm::vec3 p = hit + glm::vec3(float(dx) * eps, 0.0f, float(dz) * eps);
                        p = glm::clamp(p, b.center - b.half, b.center + b.half); // stay on the face
                        best = std::min(best, max_diff(gpu, expected(b, p, n)));
                    }
            }
            ++r.compared;
            sum += best;
            r.over += best > 2;
            if (int(b.material) != int(Material::glow))
                ++r.kinds[std::size_t(gi::classify_surface(frame.in.walls, frame.in.window, hit, n))];
            if (best > r.worst) {
                r.worst = best;
                r.worst_at = {x, y};
                r.worst_gpu = gpu;
                r.worst_ref = expected(b, hit, n);
            }
        }
    r.mean = r.compared ? sum / r.compared : 0.0;
    return r;
}

void expect_close(const PixelComparison& r) {
    EXPECT_EQ(r.over, 0) << "worst at (" << r.worst_at.x << ", " << r.worst_at.y << "): gpu " << r.worst_gpu[0] << " "
                         << r.worst_gpu[1] << " " << r.worst_gpu[2] << ", reference " << r.worst_ref[0] << " "
                         << r.worst_ref[1] << " " << r.worst_ref[2];
    EXPECT_LE(r.worst, 2);
    EXPECT_LT(r.mean, 0.5);
}

// ---- 1. lighting equals the C++ reference

TEST_F(WorldRendererTest, LightingEqualsTheCppShadingLibrary) {
    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    ASSERT_TRUE(frame->plan.run.has(gi::Pass::heat) && frame->plan.run.has(gi::Pass::directional) &&
                frame->plan.run.has(gi::Pass::wall_indirect));
    const DrawList list = world_list(*frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const render::Rgba8Image image = draw(view, list, frame.get());
    maybe_write_png(image, "lighting");

    // The GPU's own GI textures, through the C++ shading library.
    const auto shading = read_shading(*frame);
    ASSERT_TRUE(shading);
    const gi::ShadingInputs& in = shading->in;
    const scene::GiSettings& settings = frame->in.settings;
    auto expected = [&](const BoxInstance& b, glm::vec3 pos, glm::vec3 n) {
        glm::vec3 c = b.color * b.emissive;
        if (int(b.material) != int(Material::glow)) c += b.color * gi::surface_light(in, pos, n);
        return srgb8(gi::tone_map(c, settings.tone_map, settings.white_point));
    };

    const PixelComparison r = compare_pixels(image, view.camera, list, *frame, expected);
    std::printf("[ lighting ] %d pixels compared (%d ground, %d wall face, %d wall top), %d on edges skipped, "
                "%d near texel boundaries (compared at +-eps); max error %d/255, mean %.4f/255\n",
                r.compared, r.kinds[0], r.kinds[1], r.kinds[2], r.edges, r.boundary, r.worst, r.mean);
    EXPECT_GT(r.compared, target_size.x * target_size.y / 2);
    EXPECT_GT(r.kinds[0], 10000);
    EXPECT_GT(r.kinds[1], 1000);
    EXPECT_GT(r.kinds[2], 1000);
    expect_close(r);
    // Not a dark image: the comparison saw light.
    int lit = 0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) lit += image.pixels[i] + image.pixels[i + 1] > 60;
    EXPECT_GT(lit, target_size.x * target_size.y / 4);
}

// Seed 002's runtime knobs (BounceStyle): the world's set on ground and walls, the
// characters' on the crate, each pixel as the C++ twin computes it from the GPU's own GI
// textures: max(albedo x (light - bounce) + reflected_bounce(style, bounce, albedo), 0) +
// emission. The image must differ from the plain one (the knobs act), and a grey surface
// keeps its light under `self` alone (its albedo has no chroma).
TEST_F(WorldRendererTest, BounceKnobsReshapeTheBounceAsTheCppTwin) {
    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    const DrawList list = world_list(*frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const render::Rgba8Image plain = draw(view, list, frame.get());
    view.world_bounce = {0.2f, 0.6f};
    view.character_bounce = {0.0f, 1.0f};
    const render::Rgba8Image image = draw(view, list, frame.get());
    maybe_write_png(image, "bounce_knobs");
    const auto shading = read_shading(*frame);
    ASSERT_TRUE(shading);
    const scene::GiSettings& settings = frame->in.settings;
    auto expected = [&](const BoxInstance& b, glm::vec3 pos, glm::vec3 n) {
        glm::vec3 c = b.color * b.emissive;
        if (int(b.material) != int(Material::glow)) {
            const bool world = int(b.material) == int(Material::ground) || int(b.material) == int(Material::wall);
            const game::BounceStyle& style = world ? view.world_bounce : view.character_bounce;
            const glm::vec3 light = gi::surface_light(shading->in, pos, n);
            const glm::vec3 bounce = gi::surface_bounce(shading->in, pos, n);
            c += glm::max(b.color * (light - bounce) + game::reflected_bounce(style, bounce, b.color), glm::vec3(0.0f));
        }
        return srgb8(gi::tone_map(c, settings.tone_map, settings.white_point));
    };
    const PixelComparison r = compare_pixels(image, view.camera, list, *frame, expected);
    std::printf("[ bounce knobs ] %d pixels compared, max error %d/255, mean %.4f/255\n", r.compared, r.worst, r.mean);
    EXPECT_GT(r.compared, target_size.x * target_size.y / 2);
    expect_close(r);
    int changed = 0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4)
        changed += std::abs(int(image.pixels[i]) - int(plain.pixels[i])) + std::abs(int(image.pixels[i + 2]) - int(plain.pixels[i + 2])) > 6;
    std::printf("[ bounce knobs ] %d of %d pixels changed by more than 6/255\n", changed, target_size.x * target_size.y);
    EXPECT_GT(changed, target_size.x * target_size.y / 10);
    // The twin itself: a grey albedo has no chroma (self leaves it), bleed 1 reflects as white.
    const glm::vec3 orange(1.0f, 0.5f, 0.1f);
    EXPECT_EQ(game::reflected_bounce({0.0f, 0.0f}, orange, glm::vec3(0.5f)), orange * 0.5f);
    EXPECT_EQ(game::reflected_bounce({1.0f, 1.0f}, orange, glm::vec3(0.05f)), orange);
    // An orange wall under orange bounce with self 0: the bounce's chroma along the wall's own
    // is gone, its mean (brightness) kept.
    const glm::vec3 kept = game::reflected_bounce({0.0f, 1.0f}, orange, orange);
    EXPECT_NEAR((kept.r + kept.g + kept.b) / 3.0f, (orange.r + orange.g + orange.b) / 3.0f, 1e-5f);
    EXPECT_LT(kept.r - kept.b, 0.2f * (orange.r - orange.b));
}

// ---- 2. geometry

TEST(WorldRendererProjection, RoundTripsThroughCameraRay) {
    std::vector<scene::PerspectiveCamera> cameras = {follow({0.0f, 0.0f}), follow({123.4f, -57.25f})};
    scene::PerspectiveCamera wide = follow({-3.0f, 8.0f});
    wide.fov_deg = 70.0f;
    wide.aspect = 4.0f / 3.0f;
    cameras.push_back(wide);
    scene::PerspectiveCamera down; // straight down: camera_ray's other up hint
    down.position = {5.0f, 20.0f, 5.0f};
    down.target = {5.0f, 0.0f, 5.0f};
    cameras.push_back(down);
    for (const auto& camera : cameras) {
        const glm::mat4 vp = game::WorldRenderer::view_projection(camera);
        int inside = 0;
        for (int i = 0; i <= 20; ++i)
            for (int j = 0; j <= 20; ++j)
                for (float y : {0.0f, 0.75f, 2.0f}) {
                    const glm::vec3 p = camera.target + glm::vec3(float(i - 10) * 1.37f, y, float(j - 10) * 0.91f);
                    const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
                    ASSERT_GT(clip.w, 0.0f);
                    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                    EXPECT_GT(ndc.z, 0.0f);
                    EXPECT_LT(ndc.z, 1.0f);
                    // Framebuffer [0, 1]^2, y down, as camera_ray takes it.
                    const glm::vec2 uv(ndc.x * 0.5f + 0.5f, ndc.y * 0.5f + 0.5f);
                    const game::Ray ray = game::camera_ray(camera, uv);
                    const glm::vec3 to_p = p - ray.origin;
                    const float along = glm::dot(to_p, ray.direction);
                    const float off = glm::length(to_p - ray.direction * along);
                    EXPECT_LT(off, 2e-5f * glm::length(to_p)) << "point " << p.x << " " << p.y << " " << p.z;
                    inside += uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f;
                }
        EXPECT_GT(inside, 100);
    }
    // The game's camera: screen right is +x, screen up is -z.
    const scene::PerspectiveCamera c = follow({10.0f, 10.0f});
    const glm::vec4 clip = game::WorldRenderer::view_projection(c) * glm::vec4(10.0f, 0.0f, 10.0f, 1.0f);
    EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-6f); // the target is the centre of the view
    EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-6f);
    const glm::ivec2 at = project_pixel(c, {10.0f, 0.0f, 10.0f});
    EXPECT_GT(project_pixel(c, {12.0f, 0.0f, 10.0f}).x, at.x + 10);
    EXPECT_LT(project_pixel(c, {10.0f, 0.0f, 8.0f}).y, at.y - 10);
}

DrawList flat_floor(glm::vec3 color) {
    DrawList list;
    BoxInstance floor = game::ground_box({-20.0f, -20.0f}, {40.0f, 40.0f}, color);
    floor.material = float(int(Material::glow)); // unlit, and drawn in list order (not a ground box)
    floor.emissive = 1.0f;
    list.boxes.push_back(floor);
    return list;
}

BoxInstance glow_box(glm::vec3 center, glm::vec3 half, glm::vec3 color, int mask = game::face_all) {
    BoxInstance b;
    b.center = center;
    b.half = half;
    b.material = float(int(Material::glow));
    b.face_mask = float(mask);
    b.color = color;
    b.emissive = 1.0f;
    return b;
}

// A glow colour as the target shows it without GI (default tone map, sRGB).
std::array<int, 3> glow_pixel(glm::vec3 color) {
    const scene::GiSettings defaults;
    return srgb8(gi::tone_map(color, defaults.tone_map, defaults.white_point));
}

TEST_F(WorldRendererTest, WallsOccludeTheGroundBehindThem) {
    const scene::PerspectiveCamera camera = follow({10.0f, 10.0f});
    DrawList list;
    list.boxes.push_back(glow_box({10.5f, 1.0f, 8.5f}, {0.5f, 1.0f, 0.5f}, {1, 0, 0}));
    // The floor after the wall in the list: only the depth test keeps the wall in front.
    list.boxes.push_back(flat_floor({0, 0, 1}).boxes[0]);
    WorldView view;
    view.camera = camera;
    const auto image = draw(view, list, nullptr);
    maybe_write_png(image, "occlusion");
    const std::array<int, 3> red = glow_pixel({1, 0, 0}), blue = glow_pixel({0, 0, 1});
    auto at = [&](glm::vec3 p) {
        const glm::ivec2 px = project_pixel(camera, p);
        return pixel(image, px.x, px.y);
    };
    EXPECT_EQ(at({10.5f, 2.0f, 8.5f}), red);  // the top
    EXPECT_EQ(at({10.5f, 1.0f, 9.0f}), red);  // the +z face, towards the camera
    EXPECT_EQ(at({10.5f, 0.0f, 7.85f}), red); // the floor just behind the wall: hidden
    EXPECT_EQ(at({10.5f, 0.0f, 9.4f}), blue); // the floor in front of it
    EXPECT_EQ(at({13.0f, 0.0f, 8.5f}), blue);
    // And drawn the other way round.
    std::swap(list.boxes[0], list.boxes[1]);
    const auto again = draw(view, list, nullptr);
    EXPECT_EQ(again.pixels, image.pixels);
}

// Issue 19: the player stays visible behind walls. DrawList::xray boxes are drawn again only
// where something nearer hides them, as a checkerboard of their colour: behind a wall, half
// the hidden pixels show the silhouette and half the wall; in the open they add nothing.
TEST_F(WorldRendererTest, XraySilhouetteShowsOnlyWhereTheBoxIsHidden) {
    const scene::PerspectiveCamera camera = follow({10.5f, 9.0f});
    WorldView view;
    view.camera = camera;
    const glm::vec3 player{10.5f, 0.42f, 9.0f}, half{0.26f, 0.42f, 0.2f};
    const glm::vec3 green{0.0f, 1.0f, 0.0f};
    auto render = [&](bool wall, bool xray, glm::vec3 at) {
        DrawList list = flat_floor({0, 0, 1});
        if (wall) list.boxes.push_back(glow_box({10.5f, 1.0f, 10.0f}, {0.5f, 1.0f, 0.5f}, {1, 0, 0})); // in front
        list.boxes.push_back(glow_box(at, half, {1, 1, 0}));
        if (xray) list.xray.push_back(glow_box(at, half, green));
        return draw(view, list, nullptr);
    };
    const std::array<int, 3> red = glow_pixel({1, 0, 0});
    auto silhouette = [](const render::Rgba8Image& image) {
        int n = 0;
        for (std::size_t i = 0; i < image.pixels.size(); i += 4)
            n += image.pixels[i] == 0 && image.pixels[i + 1] == 255 && image.pixels[i + 2] == 0;
        return n;
    };
    const glm::ivec2 front = project_pixel(camera, player + glm::vec3(0.0f, 0.0f, half.z));
    const auto hidden = render(true, false, player);
    ASSERT_EQ(pixel(hidden, front.x, front.y), red) << "the wall does not hide the box";
    const auto xray = render(true, true, player);
    maybe_write_png(xray, "xray");
    EXPECT_EQ(silhouette(hidden), 0);
    const int shown = silhouette(xray);
    EXPECT_GT(shown, 20) << "no silhouette behind the wall";
    // A checkerboard: around the hidden front face, silhouette and wall alternate.
    int green_px = 0, red_px = 0;
    for (int dy = -2; dy < 2; ++dy)
        for (int dx = -2; dx < 2; ++dx) {
            const auto c = pixel(xray, front.x + dx, front.y + dy);
            green_px += c == std::array<int, 3>{0, 255, 0};
            red_px += c == red;
        }
    EXPECT_EQ(green_px, 8);
    EXPECT_EQ(red_px, 8);
    // Out in the open (two tiles west of the wall) the x-ray adds nothing.
    const glm::vec3 open = player - glm::vec3(2.0f, 0.0f, 0.0f);
    EXPECT_EQ(render(true, true, open).pixels, render(true, false, open).pixels);
    // A late box (the player's own backpack in front of its body) is drawn after the x-ray
    // pass: it hides the body, yet no silhouette shows on it.
    DrawList own = flat_floor({0, 0, 1});
    own.boxes.push_back(glow_box(player, half, {1, 1, 0}));
    own.late.push_back(glow_box(player + glm::vec3(0.0f, 0.1f, half.z + 0.06f), {0.3f, 0.5f, 0.05f}, {1, 0, 0}));
    own.xray.push_back(glow_box(player, half, green));
    const auto backpack = draw(view, own, nullptr);
    maybe_write_png(backpack, "xray_backpack");
    EXPECT_EQ(silhouette(backpack), 0);
    EXPECT_EQ(pixel(backpack, front.x, front.y), red) << "the late box is not drawn in front";
}

// ---- per-texel light (docs/texel.md): a texel_lit box's faces take their texel's light

// A box lit per texel by a checkerboard of light (bright and dim texels): every texel's centre
// shows its own light x albedo (no GI here), neighbours differ, so the raster picks texels by
// the model's layout with nearest filtering. Without texel light the box is a plain prop.
TEST_F(WorldRendererTest, TexelLitFacesTakeTheLightOfTheirTexels) {
    const scene::PerspectiveCamera camera = follow({10.5f, 10.0f});
    WorldView view;
    view.camera = camera;
    const glm::vec3 center{10.5f, 1.0f, 8.5f}, half{0.5f, 1.0f, 0.5f};
    const texel::Model model = texel::box_model(center - half, center + half, 4);
    const std::size_t texels = std::size_t(model.size) * std::size_t(model.size);
    std::vector<glm::vec4> lit(texels), albedo(texels, glm::vec4(0.9f, 0.7f, 0.5f, 1.0f)), surfaces(3 * texels, glm::vec4(0.0f));
    for (std::size_t i = 0; i < texels; ++i) {
        const int x = int(i % std::size_t(model.size)), y = int(i / std::size_t(model.size));
        lit[i] = ((x + y) & 1) ? glm::vec4(1.0f) : glm::vec4(0.2f);
    }
    const gpu::Buffer lit_buffer = vec4_buffer(lit, "test texel lit"), albedo_buffer = vec4_buffer(albedo, "test texel albedo"),
                      surface_buffer = vec4_buffer(surfaces, "test texel surfaces");
    game::TexelRecord record;
    record.texture = glm::vec4(0.0f, float(model.size), 0.0f, 0.0f);
    for (std::size_t f = 0; f < 5; ++f) record.faces[f] = glm::vec4(model.faces[f]);
    DrawList list = flat_floor({0, 0, 1});
    BoxInstance b;
    b.center = center;
    b.half = half;
    b.material = float(int(Material::texel_lit));
    b.color = glm::vec3(1.0f);
    b.emissive = 0.0f; // record 0
    list.boxes.push_back(b);
    WorldView lit_view = view;
    lit_view.texel_lit = &lit_buffer;
    lit_view.texel_albedo = &albedo_buffer;
    lit_view.texel_surfaces = &surface_buffer;
    lit_view.texel_records = std::span<const game::TexelRecord>(&record, 1);
    const auto image = draw(lit_view, list, nullptr);
    maybe_write_png(image, "texel_lit");
    const scene::GiSettings defaults;
    // The +z face (towards the camera) is 4 x 8 texels; its texel (i, j) counts i along +x and
    // j down from the top.
    const glm::ivec4 face = model.faces[2];
    ASSERT_EQ(face.z, 4);
    ASSERT_EQ(face.w, 8);
    int checked = 0;
    for (int j = 0; j < face.w; ++j)
        for (int i = 0; i < face.z; ++i) {
            const glm::vec3 at(center.x - half.x + (float(i) + 0.5f) / float(face.z) * 2.0f * half.x,
                               center.y + half.y - (float(j) + 0.5f) / float(face.w) * 2.0f * half.y, center.z + half.z);
            const glm::ivec2 px = project_pixel(camera, at);
            const std::size_t texel = std::size_t(face.y + j) * std::size_t(model.size) + std::size_t(face.x + i);
            const auto want = srgb8(gi::tone_map(glm::vec3(albedo[texel]) * glm::vec3(lit[texel]), defaults.tone_map,
                                                 defaults.white_point));
            EXPECT_LE(max_diff(pixel(image, px.x, px.y), want), 1) << "texel " << i << ", " << j;
            ++checked;
        }
    EXPECT_EQ(checked, 32);
    // No texel light in the view: a plain prop (black without GI), never a texel lookup.
    const auto plain = draw(view, list, nullptr);
    const glm::ivec2 mid = project_pixel(camera, center + glm::vec3(0.0f, 0.0f, half.z));
    EXPECT_EQ(pixel(plain, mid.x, mid.y), (std::array<int, 3>{0, 0, 0}));
}

TEST_F(WorldRendererTest, FaceMaskDropsFaces) {
    const scene::PerspectiveCamera camera = follow({10.0f, 10.0f});
    WorldView view;
    view.camera = camera;
    const glm::vec3 center{13.5f, 1.0f, 8.5f}, half{0.5f, 1.0f, 0.5f}; // right of the camera: its -x face shows
    auto render_mask = [&](int mask) {
        DrawList list = flat_floor({0, 0, 1});
        list.boxes.push_back(glow_box(center, half, {1, 0, 0}, mask));
        return draw(view, list, nullptr);
    };
    auto at = [&](const render::Rgba8Image& image, glm::vec3 p) {
        const glm::ivec2 px = project_pixel(camera, p);
        return pixel(image, px.x, px.y);
    };
    auto red_pixels = [](const render::Rgba8Image& image) {
        int n = 0;
        for (std::size_t i = 0; i < image.pixels.size(); i += 4) n += image.pixels[i] > 100;
        return n;
    };
    const std::array<int, 3> red = glow_pixel({1, 0, 0}), blue = glow_pixel({0, 0, 1});
    const auto all = render_mask(game::face_all);
    const auto no_front = render_mask(game::face_all & ~game::face_pos_z);
    const auto top = render_mask(game::face_top);
    const auto none = render_mask(0);
    maybe_write_png(no_front, "face_mask");
    const glm::vec3 front = center + glm::vec3(0.0f, -0.3f, half.z);
    EXPECT_EQ(at(all, front), red);
    EXPECT_EQ(at(no_front, front), blue); // through the missing face: the floor inside the box
    EXPECT_EQ(at(top, front), blue);
    EXPECT_EQ(at(top, center + glm::vec3(0.0f, half.y, 0.0f)), red);
    EXPECT_GT(red_pixels(all), red_pixels(no_front));
    EXPECT_GT(red_pixels(no_front), red_pixels(top));
    EXPECT_EQ(red_pixels(none), 0);
}

TEST_F(WorldRendererTest, GlowIgnoresLightAndNoGiDrawsEmissionOnly) {
    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    const DrawList list = world_list(*frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const auto lit = draw(view, list, frame.get());
    const auto dark = draw(view, list, nullptr); // view.gi == nullptr
    // Without GI and with a renderer but no inputs: the same.
    WorldView half_view = view;
    half_view.renderer = &gi();
    const auto dark2 = draw(half_view, list, nullptr);
    EXPECT_EQ(dark.pixels, dark2.pixels);
    maybe_write_png(dark, "no_gi");

    const BoxInstance& prop = list.boxes[list.boxes.size() - 2];
    const BoxInstance& flame = list.boxes.back();
    ASSERT_EQ(int(flame.material), int(Material::glow));
    const scene::GiSettings defaults;
    const glm::ivec2 flame_px = project_pixel(view.camera, flame.center + glm::vec3(0.0f, flame.half.y, 0.0f));
    const glm::ivec2 prop_px = project_pixel(view.camera, prop.center + glm::vec3(0.0f, prop.half.y, 0.0f));
    const auto flame_ref = srgb8(gi::tone_map(flame.color * flame.emissive, frame->in.settings.tone_map,
                                              frame->in.settings.white_point));
    EXPECT_LE(max_diff(pixel(lit, flame_px.x, flame_px.y), flame_ref), 1);
    EXPECT_EQ(pixel(lit, flame_px.x, flame_px.y), pixel(dark, flame_px.x, flame_px.y));
    // No GI: lit materials show their emission only, the ground is black.
    EXPECT_LE(max_diff(pixel(dark, prop_px.x, prop_px.y),
                       srgb8(gi::tone_map(prop.color * prop.emissive, defaults.tone_map, defaults.white_point))),
              1);
    EXPECT_NE(pixel(lit, prop_px.x, prop_px.y), pixel(dark, prop_px.x, prop_px.y));
    int black = 0;
    for (std::size_t i = 0; i < dark.pixels.size(); i += 4)
        black += dark.pixels[i] == 0 && dark.pixels[i + 1] == 0 && dark.pixels[i + 2] == 0;
    EXPECT_GT(black, int(dark.pixels.size() / 4) - 2000);
    // An empty list: cleared to black, nothing drawn, no crash.
    const auto empty = draw(view, DrawList{}, frame.get());
    EXPECT_TRUE(std::all_of(empty.pixels.begin(), empty.pixels.end(), [n = 0](std::uint8_t v) mutable {
        return (n++ % 4 == 3) ? v == 255 : v == 0;
    }));
}

// ---- light probes (seed 004): a lit_probes box takes the baked light from its direction

// Two crates beside each other, lit by the room's GI, and by probes that hold an orange light
// arriving from +x: the left crate shows its +x face (turned towards the light: more orange
// than without the probes), the right one its -x face (turned away: no more light than
// without). probe_face_light is the vertex stage's formula.
TEST_F(WorldRendererTest, ProbesLightAFaceFromWhereTheBakedLightComes) {
    bake::CircularHarmonics h;
    h.add_delta(0.0f, {0.3f, 0.12f, 0.02f}); // from +x: an orange glow (lava) to the east
    game::ProbeRecord record;
    for (int k = 0; k < 5; ++k) record.c[k] = glm::vec4(h.c[std::size_t(k)], 0.0f);
    const glm::vec3 toward = game::probe_face_light(record, 0.0f), away = game::probe_face_light(record, 3.14159265f);
    // Facing a light from one direction a face gets pi x its irradiance (order 2: 3.24 x the
    // fluence, pi exactly); turned away none of it (order 2: 0.1 x); side on a third (the
    // truncation's ringing; 0 exactly). Minus the fluence the ground gives it already.
    EXPECT_NEAR(toward.r, 0.3f * (1.5708f + 0.6667f), 1e-4f);
    EXPECT_GT(toward.r, toward.g);
    EXPECT_GT(toward.g, toward.b);
    EXPECT_LT(away.r, 0.0f) << "a face turned away loses the baked light the ground's fluence gave it";
    const glm::vec3 side = game::probe_face_light(record, 1.5707963f);
    EXPECT_LT(side.r, toward.r);
    EXPECT_GT(side.r, away.r);

    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    auto crates = [&](Material m) {
        DrawList list = world_list(*frame, false);
        for (float x : {9.5f, 18.5f}) {
            BoxInstance b;
            b.center = {x, 0.4f, 15.5f};
            b.half = {0.4f, 0.4f, 0.4f};
            b.material = float(int(m));
            b.color = {0.7f, 0.7f, 0.7f};
            b.emissive = 0.0f; // the record's index
            list.boxes.push_back(b);
        }
        list.probes.push_back(record);
        return list;
    };
    const auto plain = draw(view, crates(Material::prop), frame.get());
    const auto probed = draw(view, crates(Material::lit_probes), frame.get());
    maybe_write_png(probed, "probes");
    // The left crate is left of the camera (x 14): its +x face shows; the right one's -x face.
    const glm::ivec2 left = project_pixel(view.camera, {9.9f, 0.4f, 15.5f}), right = project_pixel(view.camera, {18.1f, 0.4f, 15.5f});
    const auto l0 = pixel(plain, left.x, left.y), l1 = pixel(probed, left.x, left.y);
    const auto r0 = pixel(plain, right.x, right.y), r1 = pixel(probed, right.x, right.y);
    std::printf("+x face: %d %d %d -> %d %d %d; -x face: %d %d %d -> %d %d %d\n", l0[0], l0[1], l0[2], l1[0], l1[1], l1[2],
                r0[0], r0[1], r0[2], r1[0], r1[1], r1[2]);
    EXPECT_GT(l1[0], l0[0] + 10) << "lit orange from the side the light comes from";
    EXPECT_GT(l1[0] - l1[2], l0[0] - l0[2] + 5) << "and orange, not white";
    EXPECT_LE(r1[0], r0[0]) << "the face turned away gets no more light";
}

// Issue 19: the baked light's probes reach texel-lit models too. A texel_lit crate whose record
// names a probe record takes the baked light's direction on its side faces, as a lit_probes
// box does: its +x face, turned to an orange glow from +x, is brighter and more orange than the
// same crate without the record.
TEST_F(WorldRendererTest, ProbesLightATexelLitFaceFromWhereTheBakedLightComes) {
    bake::CircularHarmonics h;
    h.add_delta(0.0f, {0.3f, 0.12f, 0.02f});
    game::ProbeRecord probe;
    for (int k = 0; k < 5; ++k) probe.c[k] = glm::vec4(h.c[std::size_t(k)], 0.0f);
    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const TexelCrate crate = texel_crate({9.5f, 0.4f, 15.5f}, glm::vec3(0.4f), 0.3f, 0.7f);
    const auto render = [&](bool with_probe) {
        DrawList list = world_list(*frame, false);
        list.probes.push_back(probe);
        return draw_crate(view, list, crate, with_probe ? 1.0f : 0.0f, 0.0f, glm::vec3(1.0f), frame.get());
    };
    const auto plain = render(false), probed = render(true);
    maybe_write_png(probed, "texel_probes");
    const glm::ivec2 px = project_pixel(view.camera, {9.9f, 0.4f, 15.5f}); // the +x face (left of the camera)
    const auto p0 = pixel(plain, px.x, px.y), p1 = pixel(probed, px.x, px.y);
    std::printf("texel-lit +x face: %d %d %d -> %d %d %d\n", p0[0], p0[1], p0[2], p1[0], p1[1], p1[2]);
    EXPECT_GT(p1[0], p0[0] + 10) << "lit orange from the side the baked light comes from";
    EXPECT_GT(p1[0] - p1[2], p0[0] - p0[2] + 5) << "and orange, not white";
}

// The GI's live probes (gi.probe_rays; docs/baked.md, "Live probes"): a crate between a lamp
// and the wall it lights takes that wall's light on the face turned to it. Its record asks for
// the live probes at its anchor (ProbeRecord::live); the same crate with a record that does not
// (and no baked light) is the plain crate. The probes the GPU captured say so too: facing the
// wall (+z) the interpolated probe gives more than it takes away, turned away it takes.
TEST_F(WorldRendererTest, LiveProbesLightAFaceFromTheLitWallItFaces) {
    // A room with a wall along z = 12 (x 7..15), a warm lamp at z 9.3 lighting its -z face,
    // the crate at z 10.8 between them. The camera looks towards -z from z 19 and 14 up: it sees
    // the crate's +z face over the wall.
    std::vector<std::string> rows(20, std::string(22, '.'));
    for (int x = 0; x < 22; ++x) rows[0][std::size_t(x)] = rows[19][std::size_t(x)] = '#';
    for (int z = 0; z < 20; ++z) rows[std::size_t(z)][0] = rows[std::size_t(z)][21] = '#';
    for (int x = 7; x < 16; ++x) rows[12][std::size_t(x)] = '#';
    scene::Scene s;
    s.walls = grid_from_rows(rows);
    s.wall_height = 1.5f;
    s.gi.resolution = 4;
    s.gi.padding = 1.1f;
    s.gi.heat_rounds = 12;
    s.gi.probe_rays = 32;
    s.point_lights.push_back({{11.0f, 9.3f}, 1.0f, {1.0f, 0.7f, 0.4f}, 0.5f, 10.0f}); // dim: the face stays off white
    auto frame = make_gi_frame(std::move(s), follow({11.0f, 10.0f}));
    ASSERT_TRUE(frame);
    ASSERT_TRUE(frame->plan.run.has(gi::Pass::probes));
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const glm::vec2 at(11.0f, 10.8f);
    auto render = [&](bool live) {
        DrawList list = world_list(*frame, false);
        BoxInstance b;
        b.center = {at.x, 0.3f, at.y};
        b.half = glm::vec3(0.3f);
        b.material = float(int(Material::lit_probes));
        b.color = {0.7f, 0.7f, 0.7f};
        b.emissive = 0.0f; // the record's index
        list.boxes.push_back(b);
        game::ProbeRecord record;
        if (live) record.live = glm::vec4(at, 1.0f, 0.0f);
        list.probes.push_back(record);
        return draw(view, list, frame.get());
    };
    const auto plain = render(false), probed = render(true);
    maybe_write_png(probed, "live_probes");
    const glm::ivec2 px = project_pixel(view.camera, {at.x, 0.3f, at.y + 0.3f}); // the +z face, towards the wall
    const auto p0 = pixel(plain, px.x, px.y), p1 = pixel(probed, px.x, px.y);
    std::printf("+z face: %d %d %d -> %d %d %d\n", p0[0], p0[1], p0[2], p1[0], p1[1], p1[2]);
    EXPECT_GT(p1[0], p0[0] + 8) << "lit by the wall it faces";

    // What the GPU captured, interpolated at the crate as the vertex stage does.
    const gi::Texture probes = read(gi::vk::Tex::probes);
    const gi::ProbeGrid g = gi::probe_grid(frame->in);
    ASSERT_EQ(probes.width, 5 * g.count.x);
    const glm::vec2 u = (at - 0.5f - glm::vec2(g.first_tile)) / 2.0f;
    const glm::ivec2 i0(int(std::floor(u.x)), int(std::floor(u.y)));
    const glm::vec2 f = u - glm::vec2(i0);
    game::ProbeRecord sum;
    float weight = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const glm::ivec2 i = i0 + glm::ivec2(k & 1, k >> 1);
        if (probes.at(5 * i.x, i.y)[3] < 0.5f) continue; // in a wall
        const float w = ((k & 1) ? f.x : 1.0f - f.x) * ((k >> 1) ? f.y : 1.0f - f.y);
        for (int h = 0; h < 5; ++h) {
            const float* v = probes.at(5 * i.x + h, i.y);
            sum.c[h] += glm::vec4(v[0], v[1], v[2], 0.0f) * w;
        }
        weight += w;
    }
    ASSERT_GT(weight, 0.0f);
    for (glm::vec4& c : sum.c) c /= weight;
    const float half_pi = 1.5707963f;
    const glm::vec3 toward = game::probe_face_light(sum, half_pi), away = game::probe_face_light(sum, -half_pi);
    std::printf("live probe at the crate: +z %.3f, -z %.3f (fluence %.3f)\n", toward.r, away.r, sum.c[0].r);
    EXPECT_GT(toward.r, 0.1f);
    EXPECT_GT(toward.r, 1.5f * toward.b) << "in the warm lamp's colour (before the tone map)";
    EXPECT_LT(away.r, 0.0f);
}

// A glowing texel-lit part (a crystal: TexelRecord.texture.w, its box's colour the tint)
// adds albedo x tint x glow to what its texels are lit with: brighter, in the tint's hue;
// without glow the same part is as before.
TEST_F(WorldRendererTest, AGlowingTexelLitPartAddsItsGlowInItsTint) {
    auto frame = lit_room_frame();
    ASSERT_TRUE(frame);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    view.art.texture_pattern = false;
    const TexelCrate crate = texel_crate({9.5f, 0.4f, 15.5f}, glm::vec3(0.4f), 0.05f, 0.8f);
    const glm::vec3 tint(0.3f, 0.6f, 1.0f);
    const auto render = [&](float glow, glm::vec3 color) {
        // No GI: the texels' own light alone (dim).
        return draw_crate(view, world_list(*frame, false), crate, 0.0f, glow, color, nullptr);
    };
    const auto plain = render(0.0f, glm::vec3(1.0f)), tinted = render(0.0f, tint), glowing = render(1.2f, tint);
    maybe_write_png(glowing, "texel_glow");
    const glm::ivec2 px = project_pixel(view.camera, {9.5f, 0.8f, 15.5f}); // the top face
    const auto p0 = pixel(plain, px.x, px.y), p1 = pixel(tinted, px.x, px.y), p2 = pixel(glowing, px.x, px.y);
    std::printf("texel-lit top: plain %d %d %d, tinted %d %d %d, glowing %d %d %d\n", p0[0], p0[1], p0[2], p1[0], p1[1],
                p1[2], p2[0], p2[1], p2[2]);
    EXPECT_LE(p1[2], p0[2] + 1) << "a tint alone does not brighten";
    EXPECT_LT(p1[0], p0[0]) << "it takes the tint's hue";
    EXPECT_GT(p2[2], p1[2] + 60) << "the glow brightens it";
    EXPECT_GT(p2[2], p2[0] + 40) << "in the tint's hue (blue over red)";
}

// ---- GI views (the HUD's): a texture over the world from above

// The distance view's display colour (game_world.frag.glsl gi_view_color, GI_VIEW 2).
glm::vec3 distance_view_color(float d) {
    if (d <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 c = glm::mix(glm::vec3(0.95f, 0.65f, 0.3f), glm::vec3(0.1f, 0.2f, 0.55f), std::exp(-0.3f * d));
    const float f = d * 0.5f - std::floor(d * 0.5f);
    return c * (f < 0.15f ? 0.55f : 1.0f);
}

// Every top face (ground and wall tops) shows the texel under it: the distance field as the
// distance ramp, the light image tone-mapped, the jump flood's wall texels as their own seed
// (white); a view whose texture the frame lacks draws the lit scene.
TEST_F(WorldRendererTest, GiViewsShowTheRadiosityTexturesFromAbove) {
    auto frame = lit_room_frame(scene::GiMethod::radiosity);
    ASSERT_TRUE(frame);
    ASSERT_TRUE(frame->plan.run.has(gi::Pass::distance_field) && frame->plan.run.has(gi::Pass::radiosity));
    const DrawList list = world_list(*frame, false);
    WorldView view;
    view.camera = std::get<scene::PerspectiveCamera>(frame->scene.view);
    const gi::HeatGrid grid = gi::radiosity_grid(frame->in);
    const gi::CameraView& window = frame->in.window.view;

    std::vector<Hit> hits(std::size_t(target_size.x * target_size.y));
    for (int y = 0; y < target_size.y; ++y)
        for (int x = 0; x < target_size.x; ++x)
            hits[std::size_t(y * target_size.x + x)] = trace(game::camera_ray(view.camera, pixel_ndc(x, y)), list);
    // Each top-face pixel well inside one grid texel, with that texel (or nullopt).
    auto texel_under = [&](int x, int y) -> std::optional<glm::ivec2> {
        const Hit& h = hits[std::size_t(y * target_size.x + x)];
        if (h.box < 0 || h.face != 4) return std::nullopt;
        const game::Ray ray = game::camera_ray(view.camera, pixel_ndc(x, y));
        const glm::vec3 hit = ray.origin + ray.direction * h.t;
        std::optional<glm::ivec2> t;
        for (float d : {-2e-3f, 2e-3f}) {
            const glm::vec2 g = (glm::vec2(hit.x + d, hit.z + d) - glm::vec2(window.min_x, window.min_z)) *
                                grid.texels_per_unit;
            const glm::ivec2 here(int(std::floor(g.x)), int(std::floor(g.y)));
            if (t && *t != here) return std::nullopt;
            t = here;
        }
        if (t->x < 0 || t->y < 0 || t->x >= grid.width || t->y >= grid.height) return std::nullopt;
        return t;
    };
    auto compare = [&](game::GiDebugView v, const char* name, auto&& expected) {
        view.gi_view = v;
        const render::Rgba8Image image = draw(view, list, frame.get());
        maybe_write_png(image, std::string("gi_view_") + name);
        EXPECT_EQ(world().gi_view_drawn(), v) << name;
        int compared = 0, worst = 0;
        for (int y = 0; y < target_size.y; ++y)
            for (int x = 0; x < target_size.x; ++x)
                if (const auto t = texel_under(x, y)) {
                    ++compared;
                    worst = std::max(worst, max_diff(pixel(image, x, y), expected(*t)));
                }
        std::printf("[ gi view %s ] %d pixels compared, max error %d/255\n", name, compared, worst);
        EXPECT_GT(compared, target_size.x * target_size.y / 3) << name;
        EXPECT_LE(worst, 1) << name;
    };

    draw(view, list, frame.get()); // the GI textures, to read back (every draw recomputes the same)
    const gi::Texture field = read(gi::Tex::distance_field);
    ASSERT_EQ(field.width, grid.width);
    int walls = 0, open = 0;
    compare(game::GiDebugView::distance, "distance", [&](glm::ivec2 t) {
        const float d = field.at(t.x, t.y)[0];
        (d > 0.0f ? open : walls) += 1;
        return srgb8(distance_view_color(d));
    });
    EXPECT_GT(walls, 500) << "wall tops seen";
    EXPECT_GT(open, 10000) << "ground seen";

    const gi::Texture light = read(gi::Tex::radiosity_light);
    const scene::GiSettings& settings = frame->in.settings;
    int bright = 0;
    compare(game::GiDebugView::light_image, "light_image", [&](glm::ivec2 t) {
        const glm::vec3 c = glm::make_vec3(light.at(t.x, t.y));
        bright += c.r + c.g + c.b > 0.05f;
        return srgb8(gi::tone_map(c, settings.tone_map, settings.white_point));
    });
    EXPECT_GT(bright, 1000) << "the light image has light in it";

    // The jump flood: a wall texel is its own nearest wall (white); open ground is a cell
    // coloured by its nearest wall texel, never white or black in a closed room.
    view.gi_view = game::GiDebugView::jump_flood;
    const render::Rgba8Image cells = draw(view, list, frame.get());
    maybe_write_png(cells, "gi_view_jump_flood");
    std::set<std::array<int, 3>> colours;
    int white_walls = 0, wall_pixels = 0;
    for (int y = 0; y < target_size.y; ++y)
        for (int x = 0; x < target_size.x; ++x)
            if (const auto t = texel_under(x, y)) {
                const std::array<int, 3> c = pixel(cells, x, y);
                const bool white = c == std::array<int, 3>{255, 255, 255};
                if (field.at(t->x, t->y)[0] <= 0.0f) {
                    ++wall_pixels;
                    white_walls += white;
                } else {
                    EXPECT_FALSE(white || c == (std::array<int, 3>{0, 0, 0})) << "open texel " << t->x << " " << t->y;
                    colours.insert(c);
                }
            }
    EXPECT_EQ(white_walls, wall_pixels);
    EXPECT_GT(colours.size(), 50u) << "one cell per nearest wall texel";

    // The heat method has no distance field: the view falls back to the lit scene.
    auto heat = lit_room_frame();
    ASSERT_TRUE(heat);
    view.gi_view = game::GiDebugView::distance;
    draw(view, world_list(*heat, false), heat.get());
    EXPECT_EQ(world().gi_view_drawn(), game::GiDebugView::lit);
}

// ---- 3. art controls

class WorldArtTest : public WorldRendererTest {
  protected:
    render::Rgba8Image render_art(const game::ArtSettings& art) {
        if (!frame_) frame_ = lit_room_frame();
        WorldView view;
        view.camera = std::get<scene::PerspectiveCamera>(frame_->scene.view);
        view.art = art;
        return draw(view, world_list(*frame_), frame_.get());
    }
    std::unique_ptr<GiFrame> frame_;
};

TEST_F(WorldArtTest, PosterizeGivesAtMostNLevelsPerChannel) {
    const auto plain = render_art({});
    std::array<std::set<int>, 3> plain_values;
    for (std::size_t i = 0; i < plain.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) plain_values[std::size_t(c)].insert(plain.pixels[i + std::size_t(c)]);
    for (int c = 0; c < 3; ++c) EXPECT_GT(plain_values[std::size_t(c)].size(), 40u);
    for (int levels : {2, 3, 5, 8}) {
        game::ArtSettings art;
        art.posterize = levels;
        const auto image = render_art(art);
        if (levels == 5) maybe_write_png(image, "posterize5");
        for (int c = 0; c < 3; ++c) {
            std::set<int> values;
            for (std::size_t i = 0; i < image.pixels.size(); i += 4) values.insert(image.pixels[i + std::size_t(c)]);
            EXPECT_LE(values.size(), std::size_t(levels)) << levels << " levels, channel " << c;
            EXPECT_GE(values.size(), 2u) << levels << " levels, channel " << c;
        }
    }
}

TEST_F(WorldArtTest, PaletteSwapUsesOnlyPaletteColours) {
    const auto palettes = game::builtin_palettes();
    ASSERT_GE(palettes.size(), 3u);
    EXPECT_TRUE(palettes[0].colors.empty()); // "off"
    for (std::size_t p = 1; p < palettes.size(); ++p) {
        ASSERT_GE(palettes[p].colors.size(), 2u);
        ASSERT_LE(palettes[p].colors.size(), std::size_t(game::max_palette_colors));
        std::set<std::array<int, 3>> allowed;
        for (glm::vec3 c : palettes[p].colors)
            allowed.insert({int(std::lround(c.r * 255.0f)), int(std::lround(c.g * 255.0f)), int(std::lround(c.b * 255.0f))});
        for (bool dither : {false, true}) {
            game::ArtSettings art;
            art.palette = int(p);
            art.dither = dither;
            const auto image = render_art(art);
            if (dither) maybe_write_png(image, std::string("palette_") + palettes[p].name);
            std::set<std::array<int, 3>> used;
            int outside = 0;
            for (int y = 0; y < int(image.height); ++y)
                for (int x = 0; x < int(image.width); ++x) {
                    const auto c = pixel(image, x, y);
                    used.insert(c);
                    outside += !allowed.count(c);
                }
            EXPECT_EQ(outside, 0) << palettes[p].name;
            EXPECT_GE(used.size(), 2u) << palettes[p].name;
        }
    }
}

TEST_F(WorldArtTest, DitherMakesAnOrderedDeterministicPattern) {
    game::ArtSettings smooth;
    smooth.texture_pattern = false; // the light's gradient alone
    game::ArtSettings banded = smooth;
    banded.posterize = 4;
    game::ArtSettings dithered = banded;
    dithered.dither = true;
    const auto reference = render_art(smooth);
    const auto bands = render_art(banded);
    const auto a = render_art(dithered);
    const auto b = render_art(dithered);
    maybe_write_png(a, "dither");
    EXPECT_EQ(a.pixels, b.pixels); // deterministic
    EXPECT_NE(a.pixels, bands.pixels);
    // Ordered: the pattern repeats every 4 pixels, so a pixel equals the one 4 to its right
    // far more often than its direct neighbour; the bands alone change only at band edges.
    auto changes = [](const render::Rgba8Image& im, int step) {
        int n = 0;
        for (int y = 0; y < int(im.height); ++y)
            for (int x = 0; x + step < int(im.width); ++x) n += pixel(im, x, y) != pixel(im, x + step, y);
        return n;
    };
    const int dither_1 = changes(a, 1), dither_4 = changes(a, 4), bands_1 = changes(bands, 1);
    std::printf("[ dither ] horizontal changes: dithered %d (step 1), %d (step 4); posterized only %d\n", dither_1,
                dither_4, bands_1);
    EXPECT_GT(dither_1, 3 * bands_1);
    EXPECT_LT(dither_4 * 2, dither_1);
    // A dither: 4x4 block means follow the smooth image more closely than the bands do.
    auto block_error = [&](const render::Rgba8Image& im) {
        double err = 0.0;
        for (int by = 0; by + 4 <= int(im.height); by += 4)
            for (int bx = 0; bx + 4 <= int(im.width); bx += 4)
                for (int c = 0; c < 3; ++c) {
                    double m = 0.0, r = 0.0;
                    for (int y = by; y < by + 4; ++y)
                        for (int x = bx; x < bx + 4; ++x) {
                            m += pixel(im, x, y)[std::size_t(c)];
                            r += pixel(reference, x, y)[std::size_t(c)];
                        }
                    err += std::abs(m - r) / 16.0;
                }
        return err;
    };
    const double e_dither = block_error(a), e_bands = block_error(bands);
    std::printf("[ dither ] 4x4 block error against the smooth image: dithered %.0f, posterized only %.0f\n", e_dither,
                e_bands);
    EXPECT_LT(e_dither, e_bands * 0.8);
    // Dither alone: at most one 8-bit step from the smooth image.
    game::ArtSettings only = smooth;
    only.dither = true;
    const auto fine = render_art(only);
    int worst = 0, changed = 0;
    for (int y = 0; y < int(fine.height); ++y)
        for (int x = 0; x < int(fine.width); ++x) {
            const int d = max_diff(pixel(fine, x, y), pixel(reference, x, y));
            worst = std::max(worst, d);
            changed += d > 0;
        }
    EXPECT_LE(worst, 1);
    EXPECT_GT(changed, 1000);
}

TEST_F(WorldArtTest, TexturePatternIsSubtleAndFollowsTheWorld) {
    game::ArtSettings off;
    off.texture_pattern = false;
    const auto plain = render_art(off);
    const auto patterned = render_art({});
    maybe_write_png(patterned, "pattern");
    int changed = 0;
    double sum = 0.0;
    for (std::size_t i = 0; i < plain.pixels.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(plain.pixels[i + c]) - int(patterned.pixels[i + c]));
            changed += d > 0;
            sum += d;
        }
    const double mean = sum / double(plain.pixels.size() / 4 * 3);
    std::printf("[ pattern ] mean change %.2f/255 per channel\n", mean);
    EXPECT_GT(changed, 10000); // visible
    EXPECT_LT(mean, 12.0);     // subtle
}

} // namespace
