// The fog pass: its texture, its row, its Vulkan recorder and its C++ reference.
#include "fog.hpp"

#include "fog_shaders.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>

namespace fog {
namespace {

using namespace lantern::gi;

// Mirrors FogParams in fog.comp.glsl field by field (checked when the pipeline is created).
struct FogParams {
    float r = 0, g = 0, b = 0, density = 0;
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0;
};

Tex fogged = Tex::builtin_count;

void record(vk::PassRecorder& r) {
    const GiWindow& w = r.in.window;
    r.cmd.bind(r.pipeline<FogParams>("fog.comp", {.proxies = false}));
    r.cmd.push_descriptors(lantern::gpu::DescriptorWrites()
                               .uniform_texel_buffer(0, r.walls())
                               .uniform_buffer(1, r.proxies())
                               .uniform_texel_buffer(2, r.view(Tex::indirect))
                               .storage_buffer(3, r.buffer(fogged)));
    auto p = r.params<FogParams>(w.width, w.height);
    p.pass = {.r = colour.r, .g = colour.g, .b = colour.b, .density = density};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

// What the shader computes, on the reference's textures.
void reference(ReferenceContext& c) {
    const GiWindow& w = c.in.window;
    const Texture& indirect = c.store.at(Tex::indirect);
    Texture out("fogged", TexFormat::rgba16f, w.width, w.height);
    const glm::vec2 centre(w.view.min_x + 0.5f * w.view.width, w.view.min_z + 0.5f * w.view.height);
    const glm::vec2 half(0.5f * w.view.width, 0.5f * w.view.height);
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            const glm::vec2 d = (p - centre) / half;
            const float t = std::clamp(std::sqrt(d.x * d.x + d.y * d.y) * 0.70710678f, 0.0f, 1.0f) * density;
            const float* v = indirect.at(x, y);
            const bool wall = c.in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)));
            const glm::vec3 mixed = wall ? glm::vec3(0.0f) : glm::mix(glm::vec3(v[0], v[1], v[2]), colour, t);
            const float values[4] = {mixed.r, mixed.g, mixed.b, 1.0f};
            out.store(x, y, values);
        }
    c.store.put(fogged, std::move(out));
}

} // namespace

Tex register_fog() {
    auto tex = add_texture({.name = "fogged", .format = TexFormat::rgba16f});
    if (!tex) {
        std::fprintf(stderr, "fog: %s\n", tex.error().message.c_str());
        std::exit(1);
    }
    fogged = *tex;
    static const Tex reads[] = {Tex::indirect};
    static const Tex writes[] = {fogged};
    auto row = add_row(lantern::scene::GiMethod::heat, Pass::blur,
                       {.name = "fog", .reads = reads, .writes = writes, .inputs = input_walls,
                        .record = record, .reference = reference, .shaders = fog_shaders_spirv});
    if (!row) {
        std::fprintf(stderr, "fog: %s\n", row.error().message.c_str());
        std::exit(1);
    }
    return fogged;
}

} // namespace fog
