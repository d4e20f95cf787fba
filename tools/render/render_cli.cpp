#include "render_cli.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/scene/loader.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lantern::tools {
namespace {

constexpr const char* usage_text =
    "usage: lantern-render SCENE.json [--out IMAGE.png] [--backend vulkan|cpu] [--dump DIR]\n"
    "                      [--timings FILE.json] [--set gi.KEY=VALUE ...] [--quiet]\n"
    "\n"
    "Renders the GI frame of a scene file (docs/scenes.md) through the whole pipeline: direct\n"
    "light (point, emissive, directional), heat-diffusion indirect light, blur, wall indirect.\n"
    "  --out IMAGE.png      the lit image of the GI window seen from above: ground, wall faces\n"
    "                       and wall tops, tone-mapped, sRGB, one pixel per GI texel\n"
    "  --backend vulkan|cpu Vulkan (default; LANTERN_VK_DEVICE picks a device) or the C++ reference\n"
    "  --dump DIR           every GI texture the frame produced, as little-endian float PFM\n"
    "  --timings FILE.json  per-pass times, texture size, GI window, device, passes left out\n"
    "  --set gi.KEY=VALUE   override a gi setting (e.g. --set gi.resolution=16)\n"
    "  --quiet              no progress output on stderr\n"
    "Exit status: 0 ok, 1 runtime failure (e.g. no Vulkan device), 2 bad input. Nothing is\n"
    "written unless the frame succeeded; every file is written atomically.\n";

struct Options {
    std::string scene;
    std::string out, dump, timings;
    std::string backend = "vulkan";
    std::vector<std::string> sets;
    bool quiet = false;
};

int fail(const std::string& message, int code) {
    std::fprintf(stderr, "lantern-render: %s\n", message.c_str());
    return code;
}

// Returns the exit code on error, nullopt when parsing succeeded.
std::optional<int> parse_args(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* flag) -> const char* {
            if (i + 1 >= argc) return nullptr;
            (void)flag;
            return argv[++i];
        };
        const char* v = nullptr;
        if (a == "--help" || a == "-h") {
            std::fputs(usage_text, stdout);
            return 0;
        } else if (a == "--quiet") {
            o.quiet = true;
        } else if (a == "--out" || a == "--dump" || a == "--timings" || a == "--backend" || a == "--set") {
            if (!(v = value(a.c_str()))) return fail(a + " needs a value (see --help)", 2);
            if (a == "--out") o.out = v;
            else if (a == "--dump") o.dump = v;
            else if (a == "--timings") o.timings = v;
            else if (a == "--backend") o.backend = v;
            else o.sets.push_back(v);
        } else if (!a.empty() && a[0] == '-') {
            return fail("unknown option '" + a + "' (see --help)", 2);
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            return fail("more than one scene file given ('" + o.scene + "' and '" + a + "')", 2);
        }
    }
    if (o.scene.empty()) return fail("no scene file given (see --help)", 2);
    if (o.backend != "vulkan" && o.backend != "cpu")
        return fail("--backend must be vulkan or cpu, not '" + o.backend + "'", 2);
    return std::nullopt;
}

nlohmann::json timings_json(const Options& o, const std::string& device, const gi::FrameInputs& in,
                            const gi::FrameResult& r) {
    nlohmann::json j;
    j["scene"] = o.scene;
    j["backend"] = o.backend;
    j["device"] = device;
    j["timing_source"] = o.backend == "vulkan" ? "GPU timestamps" : "CPU wall clock of the C++ reference";
    const gi::GiWindow& w = in.window;
    j["texture_size"] = {w.width, w.height};
    j["camera_view"] = {w.view.min_x, w.view.min_z, w.view.width, w.view.height};
    j["resolution"] = w.resolution;
    j["total_gpu_ms"] = r.total_ms;
    j["cpu_record_ms"] = r.cpu_record_ms;
    j["lights"] = {{"point", in.point_lights.size()},
                   {"emissive", in.emissive_lights.size()},
                   {"directional", in.directional_lights.size()},
                   {"shadow_proxies", in.proxies.size()}};
    nlohmann::json passes = nlohmann::json::array();
    for (const gi::PassReport& p : r.passes) {
        nlohmann::json e{{"name", gi::pass_name(p.pass)}, {"ran", p.ran}, {"gpu_ms", p.gpu_ms}};
        if (!p.ran) e["reason"] = p.reason;
        passes.push_back(e);
    }
    j["passes"] = passes;
    return j;
}

Result<void> write_outputs(const Options& o, const std::string& device, const gi::FrameInputs& in,
                           const gi::FrameResult& r) {
    if (!o.dump.empty()) {
        if (auto ok = ensure_directory(o.dump); !ok) return ok;
        for (const auto& [name, texture] : r.textures) {
            std::string error;
            const std::string path = (std::filesystem::path(o.dump) / (name + ".pfm")).string();
            if (!gi::write_pfm(texture, path, &error)) return make_error(error, 1);
        }
    }
    if (!o.out.empty()) {
        if (!r.lit) return make_error("no lit image was produced", 1);
        // PNG rows run top to bottom; show the window's maximum z at the top (north up).
        const gi::Image& img = *r.lit;
        std::vector<std::uint8_t> flipped(img.rgb.size());
        const std::size_t row = std::size_t(img.width) * 3;
        for (int y = 0; y < img.height; ++y)
            std::memcpy(&flipped[std::size_t(img.height - 1 - y) * row], &img.rgb[std::size_t(y) * row], row);
        if (auto ok = write_png(o.out, img.width, img.height, 3, flipped); !ok) return ok;
    }
    if (!o.timings.empty()) {
        if (auto ok = write_file_atomic(o.timings, timings_json(o, device, in, r).dump(2) + "\n"); !ok) return ok;
    }
    return {};
}

void print_summary(const Options& o, const std::string& device, const gi::FrameInputs& in, const gi::FrameResult& r) {
    if (o.quiet) return;
    std::fprintf(stderr, "lantern-render: %s, %d x %d texels (%d per unit), window [%g, %g] + [%g x %g], %s\n",
                 o.backend.c_str(), in.window.width, in.window.height, in.window.resolution, in.window.view.min_x,
                 in.window.view.min_z, in.window.view.width, in.window.view.height, device.c_str());
    for (const gi::PassReport& p : r.passes) {
        if (p.ran)
            std::fprintf(stderr, "  %-14s %9.3f ms\n", gi::pass_name(p.pass), p.gpu_ms);
        else
            std::fprintf(stderr, "  %-14s      left out: %s\n", gi::pass_name(p.pass), p.reason.c_str());
    }
    std::fprintf(stderr, "  %-14s %9.3f ms\n", "total", r.total_ms);
}

} // namespace

int render_main(int argc, char** argv) {
    Options o;
    if (auto code = parse_args(argc, argv, o)) return *code;
    auto scene = scene::load_scene(o.scene);
    if (!scene) return fail(scene.error().message, scene.error().exit_code);
    for (const std::string& s : o.sets)
        if (auto ok = scene::apply_override(*scene, s); !ok) return fail(ok.error().message, ok.error().exit_code);

    std::string why;
    auto window = gi::compute_window(scene->view, scene->gi.padding, scene->gi.resolution, &why);
    if (!window) return fail(o.scene + ": no GI for this view: " + why, 1);
    const gi::FrameInputs in = gi::gather_frame_inputs(*scene, *window);
    const gi::PassPlan plan = gi::plan_passes(in, !o.out.empty());
    if (!o.quiet)
        std::fprintf(stderr, "lantern-render: %s: %zu point, %zu emissive, %zu directional lights, %zu proxies in view\n",
                     o.scene.c_str(), in.point_lights.size(), in.emissive_lights.size(), in.directional_lights.size(),
                     in.proxies.size());

    gi::FrameResult result;
    std::string device_name;
    if (o.backend == "cpu") {
        jobs::JobSystem jobs;
        device_name = "C++ reference (" + std::to_string(jobs.thread_count()) + " threads)";
        result = gi::run_reference_frame(in, plan, {&jobs});
    } else {
        auto device = gpu::Device::create();
        if (!device) return fail(device.error().message + " (try --backend cpu)", 1);
        device_name = (*device)->name();
        auto renderer = gi::vk::Renderer::create(**device);
        if (!renderer) return fail(renderer.error().message, renderer.error().exit_code);
        auto frame = gi::run_vulkan_frame(**renderer, in, plan);
        if (!frame) return fail(o.scene + ": " + frame.error().message, frame.error().exit_code);
        result = std::move(frame.value());
    }
    print_summary(o, device_name, in, result);
    if (auto ok = write_outputs(o, device_name, in, result); !ok) return fail(ok.error().message, 1);
    return 0;
}

} // namespace lantern::tools
