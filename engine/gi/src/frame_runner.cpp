#include "lantern/gi/frame_runner.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <algorithm>

namespace lantern::gi {
namespace {

// Every row of the frame's method, in pipeline order, with whether it ran and why not.
void report_passes(FrameResult& r, const FrameInputs& in, const PassPlan& plan) {
    for (const PassRow* row : method(in.settings.method).rows)
        r.passes.push_back({row->pass, plan.run.has(row->pass), std::string(plan.reason[int(row->pass)]), 0.0, {}});
}

void add_time(FrameResult& r, Pass pass, double ms) {
    for (PassReport& p : r.passes)
        if (p.pass == pass) p.gpu_ms = ms;
    r.total_ms += ms;
}

void add_part_time(FrameResult& r, Pass pass, const char* name, double ms) {
    for (PassReport& p : r.passes) {
        if (p.pass != pass) continue;
        auto part = std::find_if(p.parts.begin(), p.parts.end(), [&](const PartReport& q) { return q.name == name; });
        if (part == p.parts.end()) part = p.parts.insert(p.parts.end(), {name, 0.0});
        part->gpu_ms += ms;
    }
}

} // namespace

FrameResult run_reference_frame(const FrameInputs& in, const PassPlan& plan, const RefOptions& options) {
    FrameResult r;
    report_passes(r, in, plan);
    ReferenceStore store;
    execute_reference(in, plan, plan.run, options, store, [](void* user, Pass pass, std::int64_t start, std::int64_t end) {
        add_time(*static_cast<FrameResult*>(user), pass, double(end - start) * 1e-6);
    }, &r);
    for (Tex t : contract_textures([&](Tex held) { return store.find(held) != nullptr; })) {
        Texture& texture = *store.textures[std::size_t(t)];
        std::string name = texture.name;
        r.textures.emplace(std::move(name), std::move(texture));
    }
    r.lit = std::move(store.lit);
    return r;
}

Result<FrameResult> run_vulkan_frame(vk::Renderer& renderer, const FrameInputs& in, const PassPlan& plan,
                                     bool read_textures) {
    if (auto ok = renderer.prepare(in, plan); !ok) return ok.error();
    FrameResult r;
    report_passes(r, in, plan);
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
        if (t.part)
            add_part_time(r, t.pass, t.part, t.gpu_ms);
        else
            add_time(r, t.pass, t.gpu_ms);
    }
    if (!read_textures) return r;
    for (Tex t : contract_textures([&](Tex held) { return renderer.has(held); })) {
        Texture texture = renderer.read_back(t);
        std::string name = texture.name;
        r.textures.emplace(std::move(name), std::move(texture));
    }
    if (plan.run.has(Pass::lit)) r.lit = Image{in.window.width, in.window.height, renderer.read_back_lit_rgb()};
    return r;
}

} // namespace lantern::gi
