// Read back of the renderer's textures and wall buffer (tests and tools: blocking), and
// the copy-kernel baseline the GI benchmark compares each pass with.
#include "lantern/gi/vulkan/pass_recorder.hpp"
#include "vulkan/renderer_internal.hpp"

#include "lantern/gi/gather.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/gi/reference_indirect.hpp"

#include <algorithm>
#include <cstring>

namespace lantern::gi::vk {

Texture Renderer::read_back(Tex t) { return read_back(t, tex_name(t)); }

Texture Renderer::read_back(Tex t, const char* name) {
    const GpuTexture& g = textures_[int(t)];
    LANTERN_ASSERT(bool(g.buffer), "read_back of a texture this frame did not allocate");
    Texture out(name, g.format, g.width, g.height);
    const auto bytes = device_.read_back(g.buffer);
    const int bpt = bytes_per_texel(g.format);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const std::byte* src = bytes.data() + (std::size_t(y) * std::size_t(g.pitch) + std::size_t(x)) * std::size_t(bpt);
            float* dst = out.at(x, y);
            if (g.format == TexFormat::rgba16f) {
                for (int c = 0; c < 4; ++c) {
                    std::uint16_t h;
                    std::memcpy(&h, src + 2 * c, 2);
                    dst[c] = half_to_float(h);
                }
            } else {
                for (int c = 0; c < bpt; ++c) dst[c] = unorm8_to_float(std::uint8_t(src[c]));
            }
        }
    return out;
}

std::vector<std::uint8_t> Renderer::read_back_lit_rgb() {
    const GpuTexture& g = textures_[int(Tex::lit)];
    LANTERN_ASSERT(bool(g.buffer), "read_back_lit_rgb without a lit pass");
    const auto bytes = device_.read_back(g.buffer);
    std::vector<std::uint8_t> rgb(std::size_t(g.width) * std::size_t(g.height) * 3);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(std::size_t(y) * std::size_t(g.width) + std::size_t(x)) * 3 + std::size_t(c)] =
                    std::uint8_t(bytes[(std::size_t(y) * std::size_t(g.pitch) + std::size_t(x)) * 4 + std::size_t(c)]);
    return rgb;
}

std::vector<std::uint8_t> Renderer::read_back_walls() {
    if (!walls_) return {};
    const auto bytes = device_.read_back(walls_);
    std::vector<std::uint8_t> out(bytes.size());
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

// ---- benchmark baseline

std::vector<std::uint64_t> Renderer::pass_bytes_written(Pass pass, const FrameInputs& in) {
    const std::uint64_t texels = std::uint64_t(pitch_of(in.window.width)) * std::uint64_t(in.window.height);
    const HeatGrid g = heat_grid(in.window, in.settings.heat_scale);
    const std::uint64_t heat_texels = std::uint64_t(pitch_of(g.width)) * std::uint64_t(g.height);
    switch (pass) {
    case Pass::conduction:
    case Pass::ao: return {texels};
    case Pass::direct:
    case Pass::directional: return {texels * (8 + 2 + 4 * 8)};
    case Pass::emission: return {texels * 8};
    case Pass::heat: {
        std::vector<std::uint64_t> out{heat_texels * 8, heat_texels * 4};
        for (int r = 0; r < in.settings.heat_rounds; ++r) out.push_back(heat_texels * 8);
        out.push_back(texels * 8);
        return out;
    }
    case Pass::blur: return {texels * 8, texels * 8};
    case Pass::wall_indirect: return {texels * 4 * 8};
    case Pass::lit: return {texels * 4};
    case Pass::distance_field: {
        const HeatGrid r = radiosity_grid(in);
        const std::uint64_t grid = std::uint64_t(pitch_of(r.width)) * std::uint64_t(r.height);
        std::vector<std::uint64_t> out(jump_flood_offsets({r.width, r.height}).size() + 1, grid * 4);
        out.push_back(grid * (4 + 8));
        return out;
    }
    case Pass::radiosity: {
        const HeatGrid r = radiosity_grid(in);
        const std::uint64_t grid = std::uint64_t(pitch_of(r.width)) * std::uint64_t(r.height);
        return {grid * 8, grid * 8, texels * 8};
    }
    case Pass::gather: {
        const HeatGrid gg = gather_grid(in);
        const std::uint64_t grid = std::uint64_t(pitch_of(gg.width)) * std::uint64_t(gg.height);
        std::vector<std::uint64_t> out(std::size_t(in.settings.gather.bounces), texels * 4 * 8); // face bounces
        out.push_back(texels * 4 * 8);                                                           // fill
        out.push_back(grid * 8);                                                                 // ground
        out.push_back(texels * 8);                                                               // upsample
        return out;
    }
    default: break; // rows added at run time: no copy baseline
    }
    return {};
}

double Renderer::time_copy_dispatches(const std::vector<std::uint64_t>& bytes_written, int repeats) {
    if (bytes_written.empty() || queries_.empty()) return 0.0;
    const std::uint64_t max_bytes = *std::max_element(bytes_written.begin(), bytes_written.end());
    // Copy texels laid out as rows of 1024 (the kernel needs a 2D grid).
    constexpr int row = 1024;
    gpu::BufferDesc desc;
    desc.size = ((max_bytes + 8 * row - 1) / (8 * row)) * (8 * row);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    desc.name = "copy src";
    gpu::Buffer src = device_.create_buffer(desc);
    desc.name = "copy dst";
    gpu::Buffer dst = device_.create_buffer(desc);
    gpu::BufferView src_view = device_.create_buffer_view(src, VK_FORMAT_R16G16B16A16_SFLOAT);
    auto queries = device_.create_timestamp_queries(1, "copy");
    if (!queries) return 0.0;
    const auto kinds = field_kinds<NoParams>();
    const auto& pipeline = this->pipeline(nullptr, "gi_copy.comp", PipelineSpec{.proxies = false}, kinds);
    std::vector<double> samples;
    for (int rep = 0; rep < repeats + 1; ++rep) { // the first run warms up
        gpu::CommandList cmd = device_.begin("copy baseline");
        cmd.fill_buffer(src, 0x3C003C00u); // 1.0 halves
        cmd.barrier_transfer_to_compute();
        queries->reset(cmd);
        const std::uint32_t region = queries->begin(cmd, "copy");
        for (std::uint64_t bytes : bytes_written) {
            const int height = int((bytes / 8 + row - 1) / row);
            cmd.bind(pipeline);
            cmd.push_descriptors(gpu::DescriptorWrites().uniform_texel_buffer(0, src_view).storage_buffer(1, dst));
            GiPassParams p{};
            p.size = glm::ivec4(row, height, row, 1);
            cmd.push_constants(p);
            dispatch_blocks(cmd, row, height);
            cmd.barrier_compute_to_compute();
        }
        queries->end(cmd, region);
        device_.submit(std::move(cmd));
        const auto result = queries->resolve();
        if (rep > 0) samples.push_back(double(result.regions[0].duration_ns) * 1e-6);
    }
    std::sort(samples.begin(), samples.end());
    return samples[samples.size() / 2];
}

} // namespace lantern::gi::vk
