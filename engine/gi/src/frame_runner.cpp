#include "lantern/gi/frame_runner.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/gi/reference_indirect.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

namespace lantern::gi {
namespace {

void add(FrameResult& r, Texture t) {
    std::string name = t.name;
    r.textures.emplace(std::move(name), std::move(t));
}

const Texture* find(const FrameResult& r, const char* name) {
    auto it = r.textures.find(name);
    return it == r.textures.end() ? nullptr : &it->second;
}

ShadingInputs shading_inputs(const FrameInputs& in, const FrameResult& r) {
    ShadingInputs s;
    s.frame = &in;
    s.direct = find(r, "direct");
    s.indirect = find(r, "indirect");
    s.ao = find(r, "ao");
    s.shadow = find(r, "shadow");
    for (int f = 0; f < 4; ++f) {
        s.wall_direct[f] = find(r, (std::string("wall_direct_") + face_suffix[f]).c_str());
        s.wall_indirect[f] = find(r, (std::string("wall_indirect_") + face_suffix[f]).c_str());
    }
    return s;
}

void report_passes(FrameResult& r, const PassPlan& plan) {
    for (int p = 0; p < pass_count; ++p) r.passes.push_back({Pass(p), plan.run.has(Pass(p)), plan.reason[p], 0.0});
}

} // namespace

FrameResult run_reference_frame(const FrameInputs& in, const PassPlan& plan, const RefOptions& options) {
    FrameResult r;
    report_passes(r, plan);
    auto timed = [&](Pass p, auto&& fn) {
        const std::int64_t start = now_ns();
        fn();
        r.passes[int(p)].gpu_ms = double(now_ns() - start) * 1e-6;
        r.total_ms += r.passes[int(p)].gpu_ms;
    };
    const GiWindow& w = in.window;
    DirectTextures direct{Texture("direct", TexFormat::rgba16f, w.width, w.height),
                          Texture("shadow", TexFormat::rg8, w.width, w.height),
                          {}};
    for (int f = 0; f < 4; ++f)
        direct.wall_direct[f] = Texture(std::string("wall_direct_") + face_suffix[f], TexFormat::rgba16f, w.width, w.height);
    if (plan.run.has(Pass::conduction)) timed(Pass::conduction, [&] { add(r, reference_conduction(in, options)); });
    if (plan.run.has(Pass::ao)) timed(Pass::ao, [&] { add(r, reference_ao(in, options)); });
    if (plan.run.has(Pass::direct)) timed(Pass::direct, [&] { direct = reference_direct(in, options); });
    if (plan.run.has(Pass::directional)) timed(Pass::directional, [&] { reference_directional(in, direct, options); });
    Texture emission, indirect;
    if (plan.run.has(Pass::emission)) timed(Pass::emission, [&] { emission = reference_emission(in, direct.direct, options); });
    if (plan.run.has(Pass::heat)) timed(Pass::heat, [&] { indirect = reference_heat(in, emission, direct.shadow, options); });
    if (plan.run.has(Pass::blur)) timed(Pass::blur, [&] { indirect = reference_blur(in, indirect, options); });
    std::array<Texture, 4> wall_indirect;
    if (plan.run.has(Pass::wall_indirect))
        timed(Pass::wall_indirect, [&] { wall_indirect = reference_wall_indirect(in, indirect, options); });
    add(r, std::move(direct.direct));
    add(r, std::move(direct.shadow));
    for (auto& t : direct.wall_direct) add(r, std::move(t));
    if (!emission.texels.empty()) add(r, std::move(emission));
    if (!indirect.texels.empty()) add(r, std::move(indirect));
    for (auto& t : wall_indirect)
        if (!t.texels.empty()) add(r, std::move(t));
    if (plan.run.has(Pass::lit)) timed(Pass::lit, [&] { r.lit = reference_lit_image(shading_inputs(in, r), options); });
    return r;
}

Result<FrameResult> run_vulkan_frame(vk::Renderer& renderer, const FrameInputs& in, const PassPlan& plan,
                                     bool read_textures) {
    if (auto ok = renderer.prepare(in, plan); !ok) return ok.error();
    FrameResult r;
    report_passes(r, plan);
    gpu::Device& device = renderer.device();
    const std::int64_t start = now_ns();
    gpu::CommandList cmd = device.begin("gi frame");
    renderer.begin_frame(cmd);
    renderer.upload_walls(cmd, in.walls);
    renderer.upload_lights(cmd, in);
    renderer.record_plan(cmd, in, plan);
    device.submit(std::move(cmd));
    r.cpu_record_ms = double(now_ns() - start) * 1e-6;
    for (const vk::PassTiming& t : renderer.wait_timings()) {
        r.passes[int(t.pass)].gpu_ms = t.gpu_ms;
        r.total_ms += t.gpu_ms;
    }
    if (!read_textures) return r;
    using vk::Tex;
    for (int t = 0; t < vk::tex_count; ++t) {
        const Tex tex = Tex(t);
        if (tex == Tex::heat_a || tex == Tex::heat_b || tex == Tex::heat_mask || tex == Tex::blur_temp ||
            tex == Tex::lit || int(tex) >= int(Tex::direct_point))
            continue;
        if (!renderer.has(tex)) continue;
        if (tex == Tex::emission && !plan.run.has(Pass::emission)) continue;
        if (tex == Tex::indirect && !plan.run.has(Pass::heat)) continue;
        add(r, renderer.read_back(tex));
    }
    if (plan.run.has(Pass::lit)) {
        Image img{in.window.width, in.window.height, renderer.read_back_lit_rgb()};
        r.lit = std::move(img);
    }
    return r;
}

} // namespace lantern::gi
